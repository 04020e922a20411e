// The DSM colour side channel's pass (see dsm_colour.h). Compiled by nvcc when CUDA is on.
#include "engine/dsm/dsm_colour.h"

#include "engine/scene/surface_transmittance.h"

namespace dv {

namespace {

// A walk target that keeps nothing: the pass wants only the walk's optical depths.
struct DiscardingTarget {
  DV_HD void push(float, float) {}
  DV_HD void push_step(float, float, float) {}
};

}  // namespace

bool scene_tints_light(const SceneData& scene) {
  for (const ObjectView& o : scene.host_objects())
    if (tints_light(o)) return true;
  return false;
}

void generate_colour_texels(Backend backend, const DsmGenerator& generator,
                            View<DsmColourTexel> texels) {
  const DsmGenerator g = generator;
  parallel_for(
      backend, "dsm_colour_texels", g.thread_count(), DV_KERNEL_LAMBDA(int64_t i) {
        DsmTexel t;
        if (!g.texel_of_thread(i, t)) return;
        DiscardingTarget target;
        double final_visibility = 1.0;
        ColourDepth tinted;
        g.walk(t, 1.0, target, final_visibility, &tinted);
        DsmColourTexel c;
        if (tinted.tinted_end >= 0.0 && tinted.optical_depth > 0.0) {
          c.k = vec3(tinted.optical_depth_rgb / tinted.optical_depth);
          c.tinted_end = float(tinted.tinted_end);
          c.tinted_optical_depth = float(tinted.optical_depth);
        }
        texels[t.index] = c;
      });
}

}  // namespace dv
