// Background CUDA driver start (see device_warmup.h).
#include "cuda/device_warmup.h"

#include "core/wall_phases.h"

#if defined(DEEPVOX_WITH_CUDA)
#include <cuda_runtime_api.h>
#endif

namespace dv {

CudaWarmup::CudaWarmup(bool wanted) {
#if defined(DEEPVOX_WITH_CUDA)
  if (!wanted) return;
  thread_ = std::thread([] {
    // cudaFree(nullptr) initialises the runtime and creates the primary context, nothing more.
    const cudaError_t err = cudaFree(nullptr);
    cudaGetLastError();
    mark_wall_phase(err == cudaSuccess ? "cuda context ready" : "cuda context unavailable");
  });
#else
  (void)wanted;
#endif
}

CudaWarmup::~CudaWarmup() {
  if (thread_.joinable()) thread_.join();
}

}  // namespace dv
