// Which backend can run here: CUDA when this build has it and a device answers (see execute.h).
#include "cuda/device_memory.h"
#include "cuda/execute.h"

namespace dv {

Backend default_backend() {
  return cuda_device_available() ? Backend::cuda : Backend::cpu;
}

void require_backend(Backend backend) {
  std::string why;
  if (backend == Backend::cuda && !cuda_device_available(&why))
    throw Error("backend cuda is not available: " + why);
}

}  // namespace dv
