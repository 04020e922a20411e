// The viewer's error view: per pixel, how far the current shadow method's light transmittance
// is from the exact oracle's (the `reference` shadow method, engine/oracle/transmittance.h) where
// the pixel looks. Definition (docs/viewer.md): p is the surface point the pixel sees
// (engine/raster/visible_surface.h: the nearest surface with alpha > 0 along the ray through the
// pixel centre), and
//     E(pixel) = (1 / L) * sum over the L lights of |T'(p, light) - T(p, light)|
// with T' the method's and T the oracle's answer, both through probe_transmittance (what
// `deepvox probe` computes for the point p, surface bias included). Pixels without a visible
// surface have no value. Shown as a colour map from 0 to the frame's maximum, with a legend.
#pragma once

#include <cstdint>
#include <vector>

#include "cuda/execute.h"
#include "engine/scene/scene.h"
#include "engine/scene/scene_view.h"
#include "render/io/image.h"

namespace dv {
class ShadowMethod;
}

namespace dv::viewer {

struct TransmittanceError {
  int width = 0, height = 0, lights = 0;
  std::vector<double> error;     // per pixel, rows from the top; NaN where no visible surface
  double max = 0.0, mean = 0.0;  // over the pixels with a visible surface
  int64_t pixels = 0;            // pixels with a visible surface
  uint32_t oracle_flags = 0;     // OR of the oracle's flags (limits reached) over all answers
};

// E per pixel of `camera` for `method` against a `reference` made by the shadow registry, on
// `backend` (`scene` in its memory).
TransmittanceError transmittance_error(Backend backend, const SceneData& scene,
                                       const Camera& camera, ShadowMethod& method);

// Black - red - yellow - white for t in [0, 1]: the error view's colour scale (linear values).
dvec3 error_colour(double t);
// What a pixel without a visible surface shows in the error view (dark blue-grey).
inline constexpr double kNoSurfaceGrey[3] = {0.02, 0.02, 0.05};

// The colour map of `e`: error_colour(E / e.max) per pixel (all black when e.max is 0).
Image error_image(const TransmittanceError& e);
// The legend's colour bar, `width` x `height`, 0 at the left and the maximum at the right.
Image error_legend_bar(int width, int height);

}  // namespace dv::viewer
