// Shadow method "dsm": deep shadow maps (strategies/storage/deep_shadow_maps.h). Parameters:
// dsm_param_table() (storage and storage.KEY, res, eps, filter, bias and slope for surface
// receivers (light_faces.h, receiver_depth), pre-filtering and volume steps, and the clustered maps
// of engine/dsm/light_clusters.h; lispsm without a camera acts as 0). Maps are generated when the
// scene data or the backend changes and, clustered, when the clustering no longer holds for the
// camera (DeepShadowMaps::clustering_holds).
#include <memory>
#include <vector>

#include "strategies/shadow/shadow_method.h"
#include "strategies/storage/deep_shadow_maps.h"

namespace dv {

namespace {

// Per light: its clusters' objects and faces (window in the light's face, texels).
nlohmann::json cluster_stats(const ClusteredLayout& c) {
  nlohmann::json lights = nlohmann::json::array();
  size_t face = 0;
  for (size_t l = 0; l < c.clusters.size(); ++l) {
    nlohmann::json clusters = nlohmann::json::array();
    for (const std::vector<int>& objects : c.clusters[l])
      clusters.push_back({{"objects", objects}, {"faces", nlohmann::json::array()}});
    const ShadowLight& sl = c.layout.lights[l];
    for (int i = 0; i < sl.face_count; ++i, ++face) {
      const ShadowFace& f = c.layout.faces[face];
      clusters[size_t(c.face_cluster[face])]["faces"].push_back(
          {{"eye", {f.eye.x, f.eye.y, f.eye.z}},
           {"axis", {f.axis.x, f.axis.y, f.axis.z}},
           {"texel_size", f.texel_size},
           {"world_to_clip",
            nlohmann::json(std::vector<double>(&f.projection.world_to_clip[0][0],
                                               &f.projection.world_to_clip[0][0] + 16))}});
    }
    lights.push_back({{"clusters", clusters}, {"maps", sl.face_count}});
  }
  return {{"resolution", c.resolution}, {"lights", lights}};
}

class DsmShadows final : public ShadowMethod {
 public:
  explicit DsmShadows(const StrategyParams& p) : maps_(DsmSettings::read(p)) {}
  std::string name() const override { return "dsm"; }
  const DeepShadowMaps* deep_shadow_maps() const override {
    return maps_.generations() > 0 ? &maps_ : nullptr;
  }
  nlohmann::json params() const override { return maps_.settings().params(maps_.storage()); }
  nlohmann::json stats() const override {
    nlohmann::json j = {{"maps_built", maps_.generations()}, {"prepare_calls", prepare_calls_}};
    if (maps_.generations() == 0) return j;
    nlohmann::json passes = nlohmann::json::array();
    for (const DsmPass& p : maps_.passes())
      passes.push_back({{"pass", p.name}, {"ms", p.milliseconds}});
    j["faces"] = maps_.layout().faces.size();
    j["generation_ms"] = maps_.generation_milliseconds();
    j["passes"] = passes;
    j["fragments"] = maps_.fragments();
    j["storage"] = maps_.figures();
    j["resolution"] = maps_.resolution();
    if (const ClusteredLayout* c = maps_.clusters()) {
      j["clusters"] = cluster_stats(*c);
      j["cluster_changes"] = cluster_changes_;
      j["cluster_changed"] = cluster_changed_;
    }
    return j;
  }

  ShadowSourceVariant prepare(const SceneData& scene, Backend backend,
                              const Camera* view) override {
    bool stale = prepared_for_ != &scene || backend_ != backend || maps_.generations() == 0;
    const ClusteredLayout* current = maps_.clusters();
    if (!stale && current) {
      stale = !maps_.clustering_holds(scene, view);
      cluster_changes_ += stale ? 1 : 0;
    }
    cluster_changed_.push_back(stale);
    if (stale) {
      maps_.generate(scene, backend, view);
      prepared_for_ = &scene;
      backend_ = backend;
    }
    ++prepare_calls_;
    return maps_.source();
  }

 private:
  DeepShadowMaps maps_;
  const SceneData* prepared_for_ = nullptr;
  Backend backend_ = Backend::cpu;
  int prepare_calls_ = 0;
  int cluster_changes_ = 0;            // regenerations because the clustering changed
  std::vector<bool> cluster_changed_;  // per prepare call: maps (re)generated
};

}  // namespace

void register_dsm_shadows(Registry<ShadowMethod>& registry) {
  registry.add("dsm", "deep shadow maps with an error bound", dsm_param_table(),
               [](const StrategyParams& p) { return std::make_unique<DsmShadows>(p); });
}

}  // namespace dv
