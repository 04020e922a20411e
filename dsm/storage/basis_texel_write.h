// The `write` pass shared by the storages that fold each texel's nodes into a fixed-size record
// (moments, fourier, occupancy; optical_depth_basis.h): one generation walk per texel into a
// copy of `prototype` (the storage's sink with its settings) whose `texel` points at texel t's
// record (t * stride), then the sink's write(). The `range` pass (texel_depth_ranges.h) has
// filled each record's first and last node depth before. Include only from files compiled by
// nvcc when CUDA is on: it launches a kernel.
#pragma once

#include "dsm/storage/dsm_storage.h"

namespace dv {

template <class Sink>
void write_basis_texels(const DsmGenerationContext& c, const char* kernel, const Sink& prototype,
                        int stride, View<float> data) {
  const DsmGenerator g = c.generator;
  const float eps = c.eps;
  const View<DsmTexelRecord> records = c.records;
  const Sink settings = prototype;
  parallel_for(
      c.backend, kernel, g.thread_count(), DV_KERNEL_LAMBDA(int64_t i) {
        DsmTexel t;
        if (!g.texel_of_thread(i, t)) return;
        Sink sink = settings;
        sink.texel = data.data + t.index * stride;
        const DsmTexelResult<Sink> r = g.generate(t, eps, sink);
        r.sink.write();
        records[t.index] = r.record;
      });
}

}  // namespace dv
