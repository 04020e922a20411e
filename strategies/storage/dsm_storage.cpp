// dsm_figures: the figures every storage strategy reports (see dsm_storage.h), one pass over
// the records on their backend (nvcc compiles this file when CUDA is on).
#include "strategies/storage/dsm_storage.h"

#include <algorithm>

#include "core/atomic.h"
#include "core/bits.h"
#include "core/error.h"
#include "core/math.h"
#include "cuda/buffer.h"
#include "cuda/execute.h"

namespace dv {

DsmHostNodes DsmStorage::host_nodes() const {
  throw Error("storage '" + name() + "' cannot copy its nodes out; generate with 'compact'");
}

namespace {

// The sums and maxima over the records, one counter each; errors are non-negative floats, whose
// bit patterns order like their values.
enum RecordCounter {
  kNodes,
  kNeeded,
  kMaxLayers,
  kNonEmpty,
  kOverflowed,
  kRecompressed,
  kWalkOverflows,
  kMaxErrorBits,
  kMaxOverflowErrorBits,
  kRecordCounters
};

}  // namespace

nlohmann::json dsm_figures(const DsmStorage& storage, Backend backend,
                           View<const DsmTexelRecord> records) {
  Buffer<unsigned long long> counters(memory_of(backend), kRecordCounters, "dsm figure counters");
  counters.fill_zero();
  unsigned long long* const c = counters.data();
  // Each thread folds kRecordsPerThread records (thread t takes t, t + threads, ...: adjacent
  // threads read adjacent records) into registers before its nine combined atomics, so the
  // combining shuffles run once per kRecordsPerThread records instead of once per record.
  constexpr int64_t kRecordsPerThread = 32;
  const int64_t threads = (records.size + kRecordsPerThread - 1) / kRecordsPerThread;
  parallel_for(
      backend, "dsm_figures", threads, DV_KERNEL_LAMBDA(int64_t t) {
        using U = unsigned long long;
        U sums[kRecordCounters] = {};
        for (int64_t i = t; i < records.size; i += threads) {
          const DsmTexelRecord r = records[i];
          const U error_bits = r.error > 0.0f ? U(float_bits(r.error)) : U(0);  // NaN, -0: none
          const bool overflowed =
              r.flags & (kDsmStorageOverflow | kDsmRecompressed | kDsmNodesMerged);
          sums[kNodes] += U(r.stored);
          sums[kNeeded] += U(r.nodes);
          sums[kMaxLayers] = max_value(sums[kMaxLayers], U(r.stored));
          sums[kNonEmpty] += U(r.stored > 0 ? 1 : 0);
          sums[kOverflowed] += U(overflowed ? 1 : 0);
          sums[kRecompressed] += U((r.flags & kDsmRecompressed) ? 1 : 0);
          sums[kWalkOverflows] += U((r.flags & kDsmWalkOverflow) ? 1 : 0);
          sums[kMaxErrorBits] = max_value(sums[kMaxErrorBits], error_bits);
          sums[kMaxOverflowErrorBits] =
              max_value(sums[kMaxOverflowErrorBits], overflowed ? error_bits : U(0));
        }
        atomic_add_combined(c + kNodes, sums[kNodes]);
        atomic_add_combined(c + kNeeded, sums[kNeeded]);
        atomic_max_combined(c + kMaxLayers, sums[kMaxLayers]);
        atomic_add_combined(c + kNonEmpty, sums[kNonEmpty]);
        atomic_add_combined(c + kOverflowed, sums[kOverflowed]);
        atomic_add_combined(c + kRecompressed, sums[kRecompressed]);
        atomic_add_combined(c + kWalkOverflows, sums[kWalkOverflows]);
        atomic_max_combined(c + kMaxErrorBits, sums[kMaxErrorBits]);
        atomic_max_combined(c + kMaxOverflowErrorBits, sums[kMaxOverflowErrorBits]);
      });
  const std::vector<unsigned long long> n = counters.to_vector();
  const auto count = [&](int k) { return int64_t(n[size_t(k)]); };
  const auto error = [&](int k) { return double(bits_float(uint32_t(n[size_t(k)]))); };
  const int64_t nodes = count(kNodes), non_empty = count(kNonEmpty);
  const double texels = double(std::max<int64_t>(records.size, 1));
  return {{"bytes_allocated", storage.bytes_allocated()},
          {"bytes_in_nodes", nodes * storage.bytes_per_node()},
          {"nodes", nodes},
          {"nodes_needed", count(kNeeded)},
          {"texels", records.size},
          {"mean_layers", double(nodes) / texels},
          {"mean_layers_nonempty", non_empty ? double(nodes) / double(non_empty) : 0.0},
          {"max_layers", count(kMaxLayers)},
          {"max_error", error(kMaxErrorBits)},
          {"overflowed_texels", count(kOverflowed)},
          {"overflow_max_error", error(kMaxOverflowErrorBits)},
          {"recompressed_texels", count(kRecompressed)},
          {"walk_overflow_texels", count(kWalkOverflows)},
          {"strategy", storage.own_figures()}};
}

}  // namespace dv
