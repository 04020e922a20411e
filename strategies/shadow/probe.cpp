// probe_transmittance: one parallel_for over (point, light) pairs (see probe.h).
#include "strategies/shadow/probe.h"

#include <chrono>
#include <variant>

#include "cuda/buffer.h"
#include "engine/scene/surface_transmittance.h"

namespace dv {

namespace {

struct ProbeAnswer {
  double transmittance;
  uint32_t flags;
  dvec3 rgb;
};

// A probe point on a surface (by the oracle's convention) is a surface receiver; see
// probe_receiver.
template <class Source>
void probe_points(Backend backend, const SceneView& s, const Source& source, int lights,
                  View<const dvec3> points, View<ProbeAnswer> out) {
  parallel_for(
      backend, "probe_transmittance", out.size, DV_KERNEL_LAMBDA(int64_t i) {
        typename Source::Cursor cursor{};
        const int light = int(i % lights);
        const ShadowReceiver r = probe_receiver(s, s.lights[light], points[i / lights]);
        const dvec3 rgb = source.transmittance_rgb(cursor, r, light);
        out[i] = {luminance(rgb), cursor.flags, rgb};
      });
}

}  // namespace

ProbeResults probe_transmittance(Backend backend, const SceneData& scene, ShadowMethod& method,
                                 const std::vector<dvec3>& points, const Camera* camera) {
  const Memory memory = memory_of(backend);
  if (scene.memory() != memory)
    throw Error("probe_transmittance: scene data is in the wrong memory");
  const int lights = int(scene.view().lights.size);
  Buffer<dvec3> pts(memory, points, "probe points");
  Buffer<ProbeAnswer> out(memory, int64_t(points.size()) * lights, "probe results");
  const ShadowSourceVariant source = method.prepare(scene, backend, camera);
  const auto start = std::chrono::steady_clock::now();
  const SceneView& view = scene.view();
  std::visit(
      [&](const auto& s) { probe_points(backend, view, s, lights, pts.const_view(), out.view()); },
      source);
  if (backend == Backend::cuda) device_synchronize("probe_transmittance");
  ProbeResults r;
  r.milliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  r.light_count = lights;
  for (const ProbeAnswer& a : out.to_vector()) {
    r.transmittance.push_back(a.transmittance);
    r.flags.push_back(a.flags);
    r.rgb.push_back(a.rgb);
  }
  return r;
}

}  // namespace dv
