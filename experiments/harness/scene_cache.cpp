// The per-run cache of scenes, probe sets and reference renders (scene_cache.h).
#include "experiments/harness/scene_cache.h"

#include "experiments/harness/image_metrics.h"
#include "render/frame/raster_render.h"
#include "render/load/scene_loader.h"
#include "strategies/shadow/probe.h"

namespace dv {

SceneCache::Entry& SceneCache::entry(const std::string& path) {
  auto it = scenes_.find(path);
  if (it != scenes_.end()) return it->second;
  Entry e;
  e.scene = load_scene(path);
  e.host = std::make_unique<SceneData>(e.scene, Memory::host);
  if (memory_of(backend_) != Memory::host)
    e.device = std::make_unique<SceneData>(e.scene, memory_of(backend_));
  return scenes_.emplace(path, std::move(e)).first->second;
}

const Scene& SceneCache::scene(const std::string& path) {
  return entry(path).scene;
}

const SceneData& SceneCache::host_data(const std::string& path) {
  return *entry(path).host;
}

const SceneData& SceneCache::data(const std::string& path) {
  Entry& e = entry(path);
  return e.device ? *e.device : *e.host;
}

const ProbeSet& SceneCache::probes(const std::string& path, int count, double medium_fraction,
                                   uint64_t seed, double isosurface) {
  const auto key = std::make_tuple(path, count, medium_fraction, seed, isosurface);
  auto it = probes_.find(key);
  if (it != probes_.end()) return it->second;
  ProbePoints points =
      make_probe_points(scene(path), host_data(path), count, medium_fraction, seed, isosurface);
  return probes_.emplace(key, with_oracle(path, std::move(points))).first->second;
}

ProbeSet SceneCache::with_oracle(const std::string& path, ProbePoints points) {
  ProbeSet set;
  set.points = std::move(points);
  auto oracle = shadow_registry().create("reference");
  const ProbeResults r = probe_transmittance(backend_, data(path), *oracle, set.points.points);
  set.exact = r.transmittance;
  set.exact_flags = r.flags;
  set.light_count = r.light_count;
  set.oracle_ms = r.milliseconds;
  return set;
}

Camera SceneCache::camera_at(const std::string& path, int width, int height) {
  Camera camera = scene(path).camera;
  camera.width = width;
  camera.height = height;
  return camera;
}

const CameraSight& SceneCache::sight(const std::string& path, int width, int height) {
  const auto key = std::make_tuple(path, width, height);
  auto it = sights_.find(key);
  if (it != sights_.end()) return it->second;
  const Camera camera = camera_at(path, width, height);
  CameraSight sight;
  sight.surface = visible_surface(Backend::cpu, host_data(path), camera);
  sight.depth = view_depths(sight.surface, camera);
  return sights_.emplace(key, std::move(sight)).first->second;
}

const ProbeSet& SceneCache::visible_probes(const std::string& path, int width, int height,
                                           int count, uint64_t seed) {
  const auto key = std::make_tuple(path, width, height, count, seed);
  auto it = visible_probes_.find(key);
  if (it != visible_probes_.end()) return it->second;
  ProbePoints points = make_visible_probe_points(sight(path, width, height).surface, count, seed);
  return visible_probes_.emplace(key, with_oracle(path, std::move(points))).first->second;
}

const StratifiedProbes& SceneCache::stratified_probes(const std::string& path, int width,
                                                      int height, const StrataSettings& settings) {
  const auto key = std::make_tuple(path, width, height, settings.camera_points,
                                   settings.stratum_min, settings.seed);
  auto it = strata_.find(key);
  if (it != strata_.end()) return it->second;
  bool media = false;
  for (const Object& o : scene(path).objects)
    media = media || o.interior.kind != InteriorKind::none;
  const Oracle oracle = [&](const std::vector<dvec3>& points) {
    const ProbeSet set = with_oracle(path, {points, std::vector<ProbeClass>(points.size())});
    return OracleAnswers{set.exact, set.light_count, set.oracle_ms};
  };
  StratifiedProbes probes =
      make_stratified_probes(scene(path), host_data(path), sight(path, width, height).surface,
                             camera_at(path, width, height), media, settings, oracle);
  return strata_.emplace(key, std::move(probes)).first->second;
}

ReferenceRender& SceneCache::reference(const std::string& path, int width, int height) {
  const auto key = std::make_tuple(path, width, height);
  auto it = references_.find(key);
  if (it != references_.end()) return it->second;
  const Camera camera = camera_at(path, width, height);
  auto oracle = shadow_registry().create("reference");
  RasterRenderResult r =
      render_raster(backend_, data(path), camera, *oracle, scene(path).background);
  ReferenceRender ref{std::move(r.render.image), r.raster_ms + r.fragment_ms, ""};
  return references_.emplace(key, std::move(ref)).first->second;
}

}  // namespace dv
