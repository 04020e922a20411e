// The per-texel records of a deep-shadow-map generation (engine/dsm/dsm_generator.h), held on
// the generation's backend one range of texels at a time: a storage that generates its faces in
// sets (compact) asks for each set's range in turn, so that the records of every texel never sit
// in device memory beside the replay scratch; a storage that generates every texel at once asks
// for one range of all. Each range is summed into the figures' counters (one pass of atomics on
// the backend) when the next is asked for or the generation finishes, and copied to the host
// when the records are kept. The renderer never reads the records; figures, export, heatmaps,
// tests and benchmarks do.
#pragma once

#include <cstdint>
#include <vector>

#include "cuda/buffer.h"
#include "cuda/execute.h"
#include "engine/dsm/dsm_generator.h"

namespace dv {

// Kernel side of the records of texels [first, first + records.size): texel t's is
// range[t.index].
struct DsmRecordRange {
  View<DsmTexelRecord> records;
  int64_t first = 0;
  DV_HD DsmTexelRecord& operator[](int64_t texel) const { return records[texel - first]; }
};

// The sums and maxima over a generation's records.
struct DsmRecordSums {
  int64_t texels = 0;
  int64_t nodes = 0;   // stored
  int64_t needed = 0;  // the compressed functions' nodes
  int64_t max_layers = 0;
  int64_t non_empty = 0;
  int64_t overflowed = 0;  // storage overflow, recompressed or nodes merged
  int64_t recompressed = 0;
  int64_t walk_overflows = 0;
  float max_error = 0.0f;
  float overflow_max_error = 0.0f;
};

class DsmRecords {
 public:
  // A generation of `texels` records on `backend`; `keep`: records() answers after it even when
  // it came in several ranges (each copied to the host as it is done). One range of all is kept
  // on the backend either way and copied on the first records() call.
  void start(Backend backend, int64_t texels, bool keep);
  // The records of texels [first, first + count) for the storage's next passes (the same range
  // asked for again gives the same records); the range before is summed (and kept) first.
  DsmRecordRange range(int64_t first, int64_t count);
  // Sums the last range; the sums of the whole generation. A last range that is not all texels
  // is freed: the device holds no records after a generation in sets.
  DsmRecordSums finish();
  // Every texel's record on the host; throws Error after a generation in several ranges that
  // did not keep them.
  const std::vector<DsmTexelRecord>& host() const;

 private:
  // Sums the current range, and copies it into host_ when `to_host`.
  void fold(bool to_host);

  Backend backend_ = Backend::cpu;
  int64_t texels_ = 0;
  bool keep_ = false;
  int ranges_ = 0;  // ranges asked for in this generation
  DsmRecordRange current_;
  Buffer<DsmTexelRecord> records_;  // the current range's (capacity reused across ranges)
  Buffer<unsigned long long> counters_;
  mutable std::vector<DsmTexelRecord> host_;
  mutable bool host_valid_ = false;
};

}  // namespace dv
