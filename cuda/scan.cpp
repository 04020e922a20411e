// exclusive_scan_in_place and exclusive_scan_queued (see scan.h). Compiled by nvcc when CUDA is
// on.
#include "cuda/scan.h"

#include <cstring>
#include <numeric>

#if defined(__CUDACC__)
#include <cub/device/device_scan.cuh>

#include "cuda/cuda_check.h"
#endif

namespace dv {

namespace {

int64_t read_value(Backend backend, const int64_t* value) {
  int64_t out = 0;
  if (backend == Backend::cuda)
    copy_to_host(&out, value, sizeof(out));
  else
    std::memcpy(&out, value, sizeof(out));
  return out;
}

}  // namespace

void exclusive_scan_queued(Backend backend, View<int64_t> values) {
  if (values.size == 0) return;
  if (backend == Backend::cuda) {
#if defined(__CUDACC__)
    const cudaStream_t stream = nullptr;  // the stream parallel_for launches on
    size_t scratch_bytes = 0;
    check_cuda(cub::DeviceScan::ExclusiveSum(nullptr, scratch_bytes, values.data, values.size),
               "exclusive_scan (scratch size)", __FILE__, __LINE__);
    // From device_allocate: a scratch that does not fit is the OutOfMemory (with the bytes asked)
    // that a suite records as its experiment's out_of_memory row.
    const Buffer<char> scratch(Memory::device, int64_t(scratch_bytes), "exclusive_scan scratch");
    check_cuda(cub::DeviceScan::ExclusiveSum(scratch.data(), scratch_bytes, values.data,
                                             values.size, stream),
               "exclusive_scan", __FILE__, __LINE__);
    return;
#else
    throw Error("exclusive_scan: CUDA scan from a build without CUDA");
#endif
  }
  std::exclusive_scan(values.data, values.data + values.size, values.data, int64_t(0));
}

int64_t exclusive_scan_in_place(Backend backend, View<int64_t> values) {
  if (values.size == 0) return 0;
  const int64_t last = read_value(backend, values.data + values.size - 1);
  exclusive_scan_queued(backend, values);
  return read_value(backend, values.data + values.size - 1) + last;
}

}  // namespace dv
