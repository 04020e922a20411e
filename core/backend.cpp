// Backend names and availability (see execute.h).
#include "core/device_memory.h"
#include "core/execute.h"

namespace dv {

const char* to_string(Backend backend) {
  return backend == Backend::cuda ? "cuda" : "cpu";
}

Backend parse_backend(const std::string& name) {
  if (name == "cpu") return Backend::cpu;
  if (name == "cuda") return Backend::cuda;
  throw InputError("--backend", "unknown backend '" + name + "' (known: cpu, cuda)");
}

Backend default_backend() {
  return cuda_device_available() ? Backend::cuda : Backend::cpu;
}

void require_backend(Backend backend) {
  std::string why;
  if (backend == Backend::cuda && !cuda_device_available(&why))
    throw Error("backend cuda is not available: " + why);
}

}  // namespace dv
