// See texel_depth_ranges.h. Compiled by nvcc when CUDA is on.
#include "strategies/storage/texel_depth_ranges.h"

#include "strategies/storage/optical_depth_basis.h"

namespace dv {

void write_texel_depth_ranges(const DsmGenerationContext& c, NodeReplay replay, View<float> data,
                              int stride) {
  const DsmGenerator g = c.generator;
  const float eps = c.eps;
  parallel_for(
      c.backend, "dsm_basis_range", g.thread_count(), DV_KERNEL_LAMBDA(int64_t i) {
        DsmTexel t;
        if (!g.texel_of_thread(i, t)) return;
        const DsmTexelResult<KeepingSink<DepthRangeSink>> r =
            g.generate(t, eps, replay.sink<DepthRangeSink>(t));
        replay.keep(i, t, r);
        const DepthRangeSink range = r.sink.inner;
        float* texel = data.data + t.index * stride;
        texel[0] = range.first;
        texel[1] = range.last;
      });
}

}  // namespace dv
