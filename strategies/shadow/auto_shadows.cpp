// Shadow method "auto": the effect planner (effect_planner.h) chooses each light's method every
// frame and the maps are cached per light. Parameters: those of `dsm` (dsm_param_table()); the
// depth maps of opaque-only lights take the same res and bias,
// PCF 2 with filter=bilinear (else 1, one nearest-texel test), and the slope that gives the same
// receiver bias as the dsm lookup (slope x reach equal). Clustering and filtering run only when
// asked (clusters > 1, filter=bilinear), never by a rule of the planner's own.
// Reuse: a light's map is kept while its method, its geometry (light_key), the content of every
// caster it reaches (casters_key) and the scene bounds its faces are fitted to (bounds_key) are
// unchanged and, clustered, while its clustering holds for the camera; so a camera move rebuilds
// nothing for unclustered lights and an edit to one object rebuilds only the maps that reach it.
// Every prepare records its plan (plan(): per light the method and why, the map built, reused or
// none and why, the passes skipped); `render` puts it into each frame's stats.
#include <memory>
#include <vector>

#include "cuda/pass_timer.h"
#include "engine/raster/fitted_light_faces.h"
#include "strategies/shadow/depth_maps.h"
#include "strategies/shadow/effect_planner.h"
#include "strategies/shadow/shadow_method.h"
#include "strategies/storage/deep_shadow_maps.h"

namespace dv {

namespace {

// One light's cached maps and what they were built from.
struct LightSlot {
  PlannedMethod method = PlannedMethod::none;
  uint64_t light_key = 0, casters_key = 0, bounds_key = 0;
  std::unique_ptr<DeepShadowMaps> deep;
  DepthMaps depth;
  int builds = 0;
};

// Why a light's map must be built now, or "" when the cached one still serves.
std::string rebuild_reason(const LightSlot& slot, const LightPlan& plan, bool backend_changed) {
  const bool has_map = slot.deep || slot.depth.res > 0;
  if (!has_map) return "no map yet";
  if (backend_changed) return "the backend changed";
  if (slot.method != plan.method) return "its method changed";
  if (slot.light_key != plan.light_key) return "the light moved or changed its cone or range";
  if (slot.bounds_key != plan.bounds_key) return "the scene bounds its faces fit changed";
  if (slot.casters_key != plan.casters_key) return "a caster it reaches changed, came or went";
  return "";
}

class AutoShadows final : public ShadowMethod {
 public:
  explicit AutoShadows(const StrategyParams& p) : dsm_(DsmSettings::read(p)) {
    storage_ = storage_registry().create(dsm_.storage, dsm_.storage_params);
    depth_.res = dsm_.resolution;
    depth_.pcf = dsm_.bilinear ? 2 : 1;
    depth_.bias = dsm_.bias;
    const double dsm_reach = dsm_.bilinear ? 1.0 : 0.5, depth_reach = 0.5 * (depth_.pcf + 1);
    depth_.slope = dsm_.slope_bias * dsm_reach / depth_reach;
  }
  std::string name() const override { return "auto"; }
  // The dsm parameters it reads (its depth maps derive theirs: stats() shows them).
  nlohmann::json params() const override { return dsm_.params(*storage_); }
  nlohmann::json stats() const override {
    return {{"prepare_calls", prepare_calls_},
            {"maps_built", maps_built_},
            {"maps_reused", maps_reused_},
            {"shadowmap", depth_.json()},
            {"plan", plan_json_}};
  }
  nlohmann::json plan() const override { return plan_json_; }

  ShadowSourceVariant prepare(const SceneData& scene, Backend backend,
                              const Camera* view) override {
    const bool backend_changed = !slots_.empty() && backend != backend_;
    backend_ = backend;
    const std::vector<LightView>& lights = scene.host_lights();
    slots_.resize(lights.size());
    std::vector<PlannedLight> plan(lights.size());
    std::vector<ShadowMapSource> depth_sources;
    std::vector<DsmSource> deep_sources;
    nlohmann::json frame_lights = nlohmann::json::array();
    const SceneView& s = scene.view();
    for (size_t l = 0; l < lights.size(); ++l) {
      const LightPlan p = plan_light(scene, int(l));
      LightSlot& slot = slots_[l];
      nlohmann::json j = {{"light", l},
                          {"type", to_string(lights[l].type)},
                          {"method", to_string(p.method)},
                          {"reason", p.reason},
                          {"casters", p.reach.casters},
                          {"opaque", p.reach.opaque},
                          {"translucent", p.reach.translucent},
                          {"media", p.reach.media},
                          {"volumes", p.reach.volumes},
                          {"volume_sampling", p.volume_sampling},
                          {"faces", p.reach.faces},
                          {"skipped", p.skipped}};
      if (p.method == PlannedMethod::none) {
        slot = LightSlot{};
        plan[l] = {PlannedKind::unshadowed, -1};
        j["map"] = "none";
        frame_lights.push_back(j);
        continue;
      }
      std::string why = rebuild_reason(slot, p, backend_changed);
      if (why.empty() && slot.deep && !slot.deep->clustering_holds(scene, view))
        why = "its clustering no longer holds for the camera";
      if (!why.empty()) {
        PassTimer timer(backend);
        build(slot, p, scene, backend, view, int(l));
        j["build_ms"] = timer.stop();
        ++maps_built_;
      } else {
        ++maps_reused_;
      }
      j["map"] = why.empty() ? "reused" : "built";
      j["map_reason"] = why.empty() ? "its light, the casters it reaches and the scene bounds "
                                      "are unchanged"
                                    : why;
      j["builds"] = slot.builds;
      j["clustered"] = slot.deep && slot.deep->clusters();
      j["filter"] =
          dsm_.bilinear ? (p.method == PlannedMethod::dsm ? "bilinear" : "pcf 2") : "none";
      const View<const LightView> light_view{s.lights.data + l, 1};
      if (p.method == PlannedMethod::shadowmap) {
        ShadowMapSource src = slot.depth.source(s, depth_);
        src.lights = light_view;
        plan[l] = {PlannedKind::depth_map, int32_t(depth_sources.size())};
        depth_sources.push_back(src);
      } else {
        DsmSource src = slot.deep->source();
        src.lights = light_view;
        plan[l] = {PlannedKind::deep_map, int32_t(deep_sources.size())};
        deep_sources.push_back(src);
      }
      frame_lights.push_back(j);
    }
    const Memory memory = memory_of(backend);
    plan_ = Buffer<PlannedLight>(memory, plan, "planned lights");
    depth_sources_ = Buffer<ShadowMapSource>(memory, depth_sources, "planned depth maps");
    deep_sources_ = Buffer<DsmSource>(memory, deep_sources, "planned deep maps");
    plan_json_ = {{"prepare", prepare_calls_++},
                  {"volume_objects", volume_objects(scene)},
                  {"lights", frame_lights}};
    return PlannedShadowSource{s.lights, plan_.const_view(), depth_sources_.const_view(),
                               deep_sources_.const_view()};
  }

 private:
  void build(LightSlot& slot, const LightPlan& p, const SceneData& scene, Backend backend,
             const Camera* view, int light) {
    slot.deep.reset();
    slot.depth = DepthMaps{};
    const SceneView& s = scene.view();
    if (p.method == PlannedMethod::shadowmap) {
      const LightMapLayout layout =
          fitted_light_map_layout(mapped_lights(scene.host_lights(), light), s.bounds,
                                  scene.host_object_bounds(), s.diagonal, depth_.res);
      slot.depth = render_depth_maps(backend, scene, layout, depth_.res, DepthCasters::surfaces,
                                     &p.reach.faces);
    } else {
      DsmSettings settings = dsm_;
      settings.light = light;
      slot.deep = std::make_unique<DeepShadowMaps>(settings);
      slot.deep->generate(scene, backend, view);
    }
    slot.method = p.method;
    slot.light_key = p.light_key;
    slot.casters_key = p.casters_key;
    slot.bounds_key = p.bounds_key;
    ++slot.builds;
  }

  DsmSettings dsm_;
  DepthMapParams depth_;
  std::unique_ptr<DsmStorage> storage_;  // echoes the storage's parameters
  Backend backend_ = Backend::cpu;
  std::vector<LightSlot> slots_;
  Buffer<PlannedLight> plan_;
  Buffer<ShadowMapSource> depth_sources_;
  Buffer<DsmSource> deep_sources_;
  nlohmann::json plan_json_;  // the last prepare's plan
  int prepare_calls_ = 0, maps_built_ = 0, maps_reused_ = 0;
};

}  // namespace

void register_auto_shadows(Registry<ShadowMethod>& registry) {
  registry.add("auto",
               "the effect planner: per light none, shadowmap or dsm as its casters need, maps "
               "cached per light (the parameters of dsm)",
               dsm_param_table(),
               [](const StrategyParams& p) { return std::make_unique<AutoShadows>(p); });
}

}  // namespace dv
