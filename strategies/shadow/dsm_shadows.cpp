// Shadow method "dsm": deep shadow maps (dsm/deep_shadow_maps.h). Parameters: storage (compact,
// texture3d, chunked, blocked; default compact), res (texels per side, default 1024), eps (error
// bound, default 0.05), filter (none | bilinear, default none), bias (world units, default 1e-4
// of the scene diagonal) and slope (texel sizes times the receiver's tangent to the light,
// default 3) for surface receivers (light_faces.h, receiver_depth), and storage.KEY
// passed to the storage strategy (e.g. storage.alloc=thesis). Maps depend on the lights and
// the casters only: they are generated when the scene data or the backend changes, never
// because the camera moved.
#include <memory>

#include "dsm/deep_shadow_maps.h"
#include "strategies/shadow/shadow_method.h"

namespace dv {

namespace {

DsmSettings dsm_settings(const StrategyParams& p) {
  DsmSettings s;
  s.storage = p.string("storage", s.storage);
  s.storage_params = p.prefixed("storage");
  s.resolution = p.integer("res", s.resolution);
  s.eps = float(p.number("eps", s.eps));
  s.bilinear = p.choice("filter", "none", {"none", "bilinear"}) == "bilinear";
  s.bias = p.number("bias", s.bias);
  s.slope_bias = p.number("slope", s.slope_bias);
  s.subrays = p.integer("subrays", s.subrays);
  s.precompressed = p.choice("volume", "midpoint", {"midpoint", "table"}) == "table";
  s.table_bins = p.integer("table_bins", s.table_bins);
  s.step_scale = p.number("step_scale", s.step_scale);
  return s;
}

class DsmShadows final : public ShadowMethod {
 public:
  explicit DsmShadows(const StrategyParams& p) : maps_(dsm_settings(p)) {}
  std::string name() const override { return "dsm"; }
  nlohmann::json params() const override {
    const DsmSettings& s = maps_.settings();
    return {{"storage", maps_.storage().name()},
            {"storage_params", maps_.storage().params()},
            {"res", s.resolution},
            {"eps", s.eps},
            {"filter", s.bilinear ? "bilinear" : "none"},
            {"bias", s.bias >= 0.0 ? nlohmann::json(s.bias) : nlohmann::json("auto")},
            {"slope", s.slope_bias},
            {"subrays", s.subrays},
            {"volume", s.precompressed ? "table" : "midpoint"},
            {"table_bins", s.table_bins},
            {"step_scale", s.step_scale}};
  }
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
    return j;
  }

  ShadowSourceVariant prepare(const SceneData& scene, Backend backend, const Camera*) override {
    if (prepared_for_ != &scene || backend_ != backend || maps_.generations() == 0) {
      maps_.generate(scene, backend);
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
};

}  // namespace

void register_dsm_shadows(Registry<ShadowMethod>& registry) {
  registry.add("dsm",
               "deep shadow maps with an error bound (params: storage, res, eps, filter, bias, "
               "slope, subrays, volume, table_bins, step_scale, storage.KEY)",
               [](const StrategyParams& p) { return std::make_unique<DsmShadows>(p); });
}

}  // namespace dv
