// sort_by_key_descending_queued (see sort.h). Compiled by nvcc when CUDA is on.
#include "cuda/sort.h"

#include <algorithm>
#include <numeric>
#include <vector>

#if defined(__CUDACC__)
#include <cub/device/device_radix_sort.cuh>

#include "cuda/cuda_check.h"
#endif

namespace dv {

void sort_by_key_descending_queued(Backend backend, View<const uint32_t> keys,
                                   View<const int32_t> values, View<int32_t> sorted_values,
                                   int key_bits) {
  if (keys.size != values.size || keys.size != sorted_values.size)
    throw Error("sort_by_key_descending: keys and values differ in size");
  if (keys.size == 0) return;
  if (backend == Backend::cuda) {
#if defined(__CUDACC__)
    const cudaStream_t stream = nullptr;  // the stream parallel_for launches on
    const int n = int(keys.size);
    size_t scratch_bytes = 0;
    check_cuda(cub::DeviceRadixSort::SortPairsDescending(
                   nullptr, scratch_bytes, keys.data, static_cast<uint32_t*>(nullptr), values.data,
                   sorted_values.data, n, 0, key_bits, stream),
               "sort_by_key_descending (scratch size)", __FILE__, __LINE__);
    // The sorted keys are not needed; CUB writes them next to its scratch.
    const size_t keys_bytes = (size_t(n) * sizeof(uint32_t) + 255) / 256 * 256;
    // From device_allocate: a scratch that does not fit is the OutOfMemory (with the bytes asked)
    // that a suite records as its experiment's out_of_memory row.
    const Buffer<char> scratch_memory(Memory::device, int64_t(keys_bytes + scratch_bytes),
                                      "sort_by_key_descending scratch");
    char* scratch = scratch_memory.data();
    check_cuda(
        cub::DeviceRadixSort::SortPairsDescending(scratch + keys_bytes, scratch_bytes, keys.data,
                                                  reinterpret_cast<uint32_t*>(scratch), values.data,
                                                  sorted_values.data, n, 0, key_bits, stream),
        "sort_by_key_descending", __FILE__, __LINE__);
    return;
#else
    throw Error("sort_by_key_descending: CUDA sort from a build without CUDA");
#endif
  }
  std::vector<int64_t> index(static_cast<size_t>(keys.size));
  std::iota(index.begin(), index.end(), int64_t(0));
  std::stable_sort(index.begin(), index.end(),
                   [&](int64_t a, int64_t b) { return keys[a] > keys[b]; });
  for (int64_t i = 0; i < keys.size; ++i) sorted_values[i] = values[index[size_t(i)]];
}

}  // namespace dv
