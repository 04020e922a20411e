// DsmRecords (see dsm_records.h): the ranges, their sums on the backend and their host copies
// (nvcc compiles this file when CUDA is on).
#include "strategies/storage/dsm_records.h"

#include <algorithm>
#include <string>

#include "core/atomic.h"
#include "core/bits.h"
#include "core/error.h"
#include "core/math.h"
#include "cuda/ensure_buffer.h"

namespace dv {

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

// Adds `records` to the counters.
void sum_records(Backend backend, View<const DsmTexelRecord> records,
                 View<unsigned long long> counters) {
  unsigned long long* const c = counters.data;
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
}

}  // namespace

void DsmRecords::start(Backend backend, int64_t texels, bool keep) {
  backend_ = backend;
  texels_ = texels;
  keep_ = keep;
  ranges_ = 0;
  current_ = {};
  host_valid_ = false;
  ensure_buffer(counters_, memory_of(backend), kRecordCounters, "dsm figure counters");
  counters_.fill_zero();
}

DsmRecordRange DsmRecords::range(int64_t first, int64_t count) {
  if (ranges_ > 0 && first == current_.first && count == current_.records.size) return current_;
  fold(keep_);
  const Memory memory = memory_of(backend_);
  if (records_.size() < count || records_.memory() != memory)
    ensure_buffer(records_, memory, count, "dsm texel records");
  ++ranges_;
  return current_ = {{records_.data(), count}, first};
}

void DsmRecords::fold(bool to_host) {
  if (ranges_ == 0) return;
  const View<const DsmTexelRecord> done{current_.records.data, current_.records.size};
  sum_records(backend_, done, counters_.view());
  if (!to_host) return;
  host_.resize(size_t(texels_));
  const std::vector<DsmTexelRecord> part = to_host_vector(done, records_.memory());
  std::copy(part.begin(), part.end(), host_.begin() + current_.first);
}

DsmRecordSums DsmRecords::finish() {
  const bool whole = ranges_ <= 1 && current_.records.size == texels_;
  fold(keep_ && !whole);
  host_valid_ = keep_ && !whole;
  if (!whole) records_ = Buffer<DsmTexelRecord>();
  const std::vector<unsigned long long> n = counters_.to_vector();
  const auto count = [&](int k) { return int64_t(n[size_t(k)]); };
  const auto error = [&](int k) { return bits_float(uint32_t(n[size_t(k)])); };
  DsmRecordSums s;
  s.texels = texels_;
  s.nodes = count(kNodes);
  s.needed = count(kNeeded);
  s.max_layers = count(kMaxLayers);
  s.non_empty = count(kNonEmpty);
  s.overflowed = count(kOverflowed);
  s.recompressed = count(kRecompressed);
  s.walk_overflows = count(kWalkOverflows);
  s.max_error = error(kMaxErrorBits);
  s.overflow_max_error = error(kMaxOverflowErrorBits);
  return s;
}

const std::vector<DsmTexelRecord>& DsmRecords::host() const {
  if (host_valid_) return host_;
  if (current_.records.size != texels_ || ranges_ > 1)
    throw Error("dsm: the per-texel records of maps generated in " + std::to_string(ranges_) +
                " sets of faces were not kept (DsmSettings::keep_records)");
  host_ = to_host_vector(View<const DsmTexelRecord>{current_.records.data, texels_},
                         memory_of(backend_));
  host_valid_ = true;
  return host_;
}

}  // namespace dv
