// The error view's |T' - T| per pixel and its colour map (see viewer_error_view.h).
#include "apps/viewer/viewer_error_view.h"

#include <algorithm>
#include <cmath>

#include "engine/raster/visible_surface.h"
#include "strategies/shadow/probe.h"
#include "strategies/shadow/shadow_method.h"

namespace dv::viewer {

TransmittanceError transmittance_error(Backend backend, const SceneData& scene,
                                       const Camera& camera, ShadowMethod& method) {
  const VisibleSurface surface = visible_surface(backend, scene, camera);
  std::vector<dvec3> points;
  for (size_t i = 0; i < surface.points.size(); ++i)
    if (surface.hit[i]) points.push_back(surface.points[i]);
  TransmittanceError e;
  e.width = surface.width;
  e.height = surface.height;
  e.error.assign(surface.points.size(), NAN);
  if (points.empty()) return e;
  auto oracle = shadow_registry().create("reference");
  const ProbeResults exact = probe_transmittance(backend, scene, *oracle, points, &camera);
  const ProbeResults approx = probe_transmittance(backend, scene, method, points, &camera);
  e.lights = exact.light_count;
  for (uint32_t f : exact.flags) e.oracle_flags |= f;
  double sum = 0.0;
  size_t point = 0;
  for (size_t i = 0; i < surface.points.size(); ++i) {
    if (!surface.hit[i]) continue;
    double total = 0.0;
    for (int l = 0; l < e.lights; ++l) {
      const size_t at = point * size_t(e.lights) + size_t(l);
      total += std::abs(approx.transmittance[at] - exact.transmittance[at]);
    }
    ++point;
    e.error[i] = e.lights > 0 ? total / e.lights : 0.0;
    e.max = std::max(e.max, e.error[i]);
    sum += e.error[i];
  }
  e.pixels = int64_t(point);
  e.mean = point > 0 ? sum / double(point) : 0.0;
  return e;
}

dvec3 error_colour(double t) {
  t = std::clamp(t, 0.0, 1.0) * 3.0;
  return {std::min(t, 1.0), std::clamp(t - 1.0, 0.0, 1.0), std::clamp(t - 2.0, 0.0, 1.0)};
}

Image error_image(const TransmittanceError& e) {
  Image image(e.width, e.height);
  for (size_t i = 0; i < e.error.size(); ++i) {
    const dvec3 c = std::isnan(e.error[i])
                        ? dvec3(kNoSurfaceGrey[0], kNoSurfaceGrey[1], kNoSurfaceGrey[2])
                        : error_colour(e.max > 0.0 ? e.error[i] / e.max : 0.0);
    for (int k = 0; k < 3; ++k) image.rgb[i * 3 + size_t(k)] = float(c[k]);
  }
  return image;
}

Image error_legend_bar(int width, int height) {
  Image bar(width, height);
  for (int x = 0; x < width; ++x) {
    const dvec3 c = error_colour(width > 1 ? double(x) / double(width - 1) : 0.0);
    for (int y = 0; y < height; ++y)
      for (int k = 0; k < 3; ++k) bar.rgb[(size_t(y) * width + x) * 3 + size_t(k)] = float(c[k]);
  }
  return bar;
}

}  // namespace dv::viewer
