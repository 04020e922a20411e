// exclusive_scan_in_place (see scan.h). Compiled by nvcc when CUDA is on.
#include "core/scan.h"

#include <numeric>

#if defined(__CUDACC__)
#include <thrust/execution_policy.h>
#include <thrust/scan.h>

#include "core/cuda_check.h"
#endif

namespace dv {

int64_t exclusive_scan_in_place(Backend backend, View<int64_t> values) {
  if (values.size == 0) return 0;
  if (backend == Backend::cuda) {
#if defined(__CUDACC__)
    int64_t last = 0;
    check_cuda(
        cudaMemcpy(&last, values.data + values.size - 1, sizeof(last), cudaMemcpyDeviceToHost),
        "exclusive_scan (last value)", __FILE__, __LINE__);
    thrust::exclusive_scan(thrust::device, values.data, values.data + values.size, values.data,
                           int64_t(0));
    int64_t before_last = 0;
    check_cuda(cudaMemcpy(&before_last, values.data + values.size - 1, sizeof(before_last),
                          cudaMemcpyDeviceToHost),
               "exclusive_scan (total)", __FILE__, __LINE__);
    return before_last + last;
#else
    throw Error("exclusive_scan_in_place: CUDA scan from a build without CUDA");
#endif
  }
  const int64_t last = values.data[values.size - 1];
  std::exclusive_scan(values.data, values.data + values.size, values.data, int64_t(0));
  return values.data[values.size - 1] + last;
}

}  // namespace dv
