// The two passes of the storages that fold each texel's nodes into a fixed-size record
// (moments, fourier, occupancy; optical_depth_basis.h): `range` (texel_depth_ranges.h) writes
// each record's first and last node depth and keeps the nodes (engine/dsm/node_replay.h); `write`
// replays texel t's nodes (or walks them again where they were not kept) into a copy of
// `prototype` (the storage's sink with its settings) whose `texel` points at texel t's record
// (t * stride), then calls the sink's write(). Include only from files compiled by nvcc when
// CUDA is on: it launches a kernel.
#pragma once

#include "engine/dsm/node_replay.h"
#include "strategies/storage/dsm_storage.h"
#include "strategies/storage/node_replay_scratch.h"
#include "strategies/storage/replay_write.h"
#include "strategies/storage/texel_depth_ranges.h"

namespace dv {

template <bool kWalk, class Sink>
void write_basis_texels(const DsmGenerationContext& c, NodeReplay replay, const char* kernel,
                        const Sink& prototype, int stride, View<float> data) {
  const DsmGenerator g = c.generator;
  const float eps = c.eps;
  const DsmRecordRange records = c.texel_records();
  const Sink settings = prototype;
  for_replay_texels<kWalk>(
      c, replay, kernel, DV_KERNEL_LAMBDA(int64_t, const DsmTexel& t) {
        Sink sink = settings;
        sink.texel = data.data + t.index * stride;
        const DsmTexelResult<Sink> r = replay.generate<kWalk>(g, t, eps, sink);
        r.sink.write();
        records[t.index] = r.record;
      });
}

// Both passes, timed as `range` and `write`, with their replay in `scratch` (begun inside the
// range pass's time).
template <class Sink>
void generate_basis_texels(const DsmGenerationContext& c, NodeReplayScratch& scratch,
                           const char* kernel, const Sink& prototype, int stride,
                           View<float> data) {
  timed_pass(c, "range", [&] { write_texel_depth_ranges(c, scratch.begin(c), data, stride); });
  timed_pass(c, "write", [&] {
    const NodeReplay replay = scratch.replay();
    run_replay_write(replay, [&]<bool kWalk>() {
      write_basis_texels<kWalk>(c, replay, kernel, prototype, stride, data);
    });
  });
  scratch.end();
}

}  // namespace dv
