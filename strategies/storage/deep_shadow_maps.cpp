// DeepShadowMaps (see deep_shadow_maps.h).
#include "strategies/storage/deep_shadow_maps.h"

#include <limits>
#include <string>
#include <vector>

#include "core/error.h"
#include "cuda/pass_timer.h"
#include "cuda/pool_peak.h"
#include "engine/dsm/dsm_colour.h"

namespace dv {

DeepShadowMaps::DeepShadowMaps(DsmSettings settings) : settings_(std::move(settings)) {
  StrategyParams::from_json(settings_.own_params()).resolved(dsm_param_table(), "dsm");
  storage_ = storage_registry().create(settings_.storage, settings_.storage_params);
}

namespace {

// One key of the dsm parameters: its declaration, how DsmSettings reads it from resolved
// parameters, and how own_params() writes it back (null for the nested storage.* items, which
// params() writes).
struct DsmKey {
  ParamSpec spec;
  void (*read)(const StrategyParams& p, const std::string& key, DsmSettings& s);
  nlohmann::json (*write)(const DsmSettings& s);
};

// Every key of DsmSettings, once: dsm_param_table(), DsmSettings::read and own_params() are
// walks over this list, so a key added here is declared, read and echoed alike.
const std::vector<DsmKey>& dsm_keys() {
  static const std::vector<DsmKey> keys = [] {
    const DsmSettings d;
    const ClusterSettings& c = d.clusters;
    constexpr double inf = std::numeric_limits<double>::infinity();
    using Params = const StrategyParams&;
    using Key = const std::string&;
    using Settings = const DsmSettings&;
    return std::vector<DsmKey>{
        {name_param("storage", d.storage, "storage strategy of the maps (`deepvox list`)"),
         [](Params p, Key k, DsmSettings& s) { s.storage = p.string(k); },
         [](Settings s) -> nlohmann::json { return s.storage; }},
        {nested_param("storage", "a parameter of the storage strategy (storage.alloc=thesis)"),
         [](Params p, Key k, DsmSettings& s) { s.storage_params = p.prefixed(k); }, nullptr},
        {integer_param("res", d.resolution, 1, kMaxRasterSide, "texels per side of each map"),
         [](Params p, Key k, DsmSettings& s) { s.resolution = p.integer(k); },
         [](Settings s) -> nlohmann::json { return s.resolution; }},
        {number_param("eps", d.eps, 0.0, inf,
                      "bound on the error of every compressed visibility function"),
         [](Params p, Key k, DsmSettings& s) { s.eps = float(p.number(k)); },
         [](Settings s) -> nlohmann::json { return s.eps; }},
        {choice_param("filter", d.bilinear ? "bilinear" : "none", {"none", "bilinear"},
                      "lookup: nearest texel or bilinear over four"),
         [](Params p, Key k, DsmSettings& s) { s.bilinear = p.string(k) == "bilinear"; },
         [](Settings s) -> nlohmann::json { return s.bilinear ? "bilinear" : "none"; }},
        {number_param("bias", d.bias, -1.0, inf,
                      "receiver depth bias in world units; < 0: 1e-4 of the scene diagonal"),
         [](Params p, Key k, DsmSettings& s) { s.bias = p.number(k); },
         [](Settings s) -> nlohmann::json { return s.bias; }},
        {number_param("slope", d.slope_bias, 0.0, inf,
                      "slope bias: texel sizes times the receiver's tangent to the light"),
         [](Params p, Key k, DsmSettings& s) { s.slope_bias = p.number(k); },
         [](Settings s) -> nlohmann::json { return s.slope_bias; }},
        {integer_choice_param("subrays", d.subrays, {1, 4, 9, 16},
                              "jittered sub-rays per texel, averaged (pre-filtering)"),
         [](Params p, Key k, DsmSettings& s) { s.subrays = p.integer(k); },
         [](Settings s) -> nlohmann::json { return s.subrays; }},
        {choice_param("volume", d.precompressed ? "table" : "midpoint", {"midpoint", "table"},
                      "volume steps: midpoint samples, or Hadwiger's pre-compressed tables"),
         [](Params p, Key k, DsmSettings& s) { s.precompressed = p.string(k) == "table"; },
         [](Settings s) -> nlohmann::json { return s.precompressed ? "table" : "midpoint"; }},
        {integer_param("table_bins", d.table_bins, 2, 1024, "bins of the pre-compressed tables"),
         [](Params p, Key k, DsmSettings& s) { s.table_bins = p.integer(k); },
         [](Settings s) -> nlohmann::json { return s.table_bins; }},
        {positive_param("step_scale", d.step_scale, "multiplies the volumes' steps in generation"),
         [](Params p, Key k, DsmSettings& s) { s.step_scale = p.number(k); },
         [](Settings s) -> nlohmann::json { return s.step_scale; }},
        {integer_param("clusters", c.max_clusters, 1, std::numeric_limits<int32_t>::max(),
                       "most clusters per light (Knecht 2011); 1: one map per light face"),
         [](Params p, Key k, DsmSettings& s) { s.clusters.max_clusters = p.integer(k); },
         [](Settings s) -> nlohmann::json { return s.clusters.max_clusters; }},
        {number_param("cluster_d0", c.d0, 0.0, inf,
                      "distance threshold of the clustering, NDC units of the face"),
         [](Params p, Key k, DsmSettings& s) { s.clusters.d0 = p.number(k); },
         [](Settings s) -> nlohmann::json { return s.clusters.d0; }},
        {integer_choice_param("lispsm", c.lispsm ? 1 : 0, {0, 1},
                              "1: cluster in the light-space perspective of the camera"),
         [](Params p, Key k, DsmSettings& s) { s.clusters.lispsm = p.integer(k) == 1; },
         [](Settings s) -> nlohmann::json { return s.clusters.lispsm ? 1 : 0; }},
        {number_param("cluster_hysteresis", c.hysteresis, 0.0, inf,
                      "fraction of cluster_d0 a distance may move before reclustering"),
         [](Params p, Key k, DsmSettings& s) { s.clusters.hysteresis = p.number(k); },
         [](Settings s) -> nlohmann::json { return s.clusters.hysteresis; }}};
  }();
  return keys;
}

}  // namespace

const ParamTable& dsm_param_table() {
  static const ParamTable table = [] {
    ParamTable specs;
    for (const DsmKey& key : dsm_keys()) specs.push_back(key.spec);
    return specs;
  }();
  return table;
}

DsmSettings DsmSettings::read(const StrategyParams& p) {
  DsmSettings s;
  for (const DsmKey& key : dsm_keys()) key.read(p, key.spec.key, s);
  return s;
}

nlohmann::json DsmSettings::params(const DsmStorage& created) const {
  nlohmann::json j = own_params();
  j["storage"] = created.name();
  const nlohmann::json own = created.params();  // items() must not outlive it
  for (const auto& [key, value] : own.items()) j["storage." + key] = value;
  return j;
}

nlohmann::json DsmSettings::own_params() const {
  nlohmann::json j = nlohmann::json::object();
  for (const DsmKey& key : dsm_keys())
    if (key.write) j[key.spec.key] = key.write(*this);
  return j;
}

ClusteredLayout DeepShadowMaps::plan_clusters(const SceneData& scene, const Camera* camera) const {
  const SceneView& s = scene.view();
  const ClusterSettings& c = settings_.clusters;
  const std::vector<LightView> lights = mapped_lights(scene.host_lights(), settings_.light);
  return clustered_light_map_layout(
      lights, scene.host_object_bounds(),
      light_distances(lights, scene.host_object_bounds(), s.bounds, s.diagonal, c, camera), c,
      settings_.resolution);
}

bool DeepShadowMaps::clustering_holds(const SceneData& scene, const Camera* camera) const {
  if (!clustered_) return true;
  const SceneView& s = scene.view();
  const std::vector<LightView> lights = mapped_lights(scene.host_lights(), settings_.light);
  const std::vector<ObjectDistances> now = light_distances(
      lights, scene.host_object_bounds(), s.bounds, s.diagonal, settings_.clusters, camera);
  return dv::clustering_holds(clusters_, now, settings_.clusters) ||
         clustered_light_map_layout(lights, scene.host_object_bounds(), now, settings_.clusters,
                                    settings_.resolution)
                 .signature == clusters_.signature;
}

void DeepShadowMaps::generate(const SceneData& scene, Backend backend, const Camera* camera) {
  passes_.clear();
  clustered_ = settings_.clusters.max_clusters > 1;
  if (clustered_) {
    PassTimer timer(backend);
    clusters_ = plan_clusters(scene, camera);
    passes_.push_back({"cluster", timer.stop()});
  }
  {
    PassTimer timer(backend);
    DsmGenerationOptions options;
    options.resolution = settings_.resolution;
    options.subrays = settings_.subrays;
    options.precompressed = settings_.precompressed;
    options.table_bins = settings_.table_bins;
    options.step_scale = settings_.step_scale;
    options.light = settings_.light;
    generation_ =
        std::make_unique<DsmGeneration>(scene, backend, options, clustered_ ? &clusters_ : nullptr);
    const double ms = timer.stop(), table_ms = generation_->table_milliseconds();
    passes_.push_back({"raster", ms - table_ms});
    if (settings_.precompressed) passes_.push_back({"table", table_ms});
  }
  const DsmGenerator& g = generation_->generator();
  records_.start(backend, g.texel_count(), settings_.keep_records);
  const DsmGenerationContext context{backend,  g,        settings_.eps,
                                     records_, &passes_, settings_.face_set_bytes};
  storage_->generate(context);
  figures_ = dsm_figures(*storage_, records_.finish());
  colour_texels_ = Buffer<DsmColourTexel>();
  if (scene_tints_light(scene)) {
    PassTimer timer(backend);
    colour_texels_ =
        Buffer<DsmColourTexel>(memory_of(backend), g.texel_count(), "dsm colour side channel");
    generate_colour_texels(backend, g, colour_texels_.view());
    passes_.push_back({"colour", timer.stop()});
    const int64_t colour_bytes = colour_texels_.bytes();
    figures_["colour_bytes"] = colour_bytes;
    figures_["bytes_allocated"] = figures_["bytes_allocated"].get<int64_t>() + colour_bytes;
  }
  const SceneView& s = scene.view();
  const View<const LightView> lights =
      settings_.light < 0 ? s.lights : View<const LightView>{s.lights.data + settings_.light, 1};
  source_ = DsmSource{lights,
                      generation_->lights(),
                      generation_->faces(),
                      storage_->reader(),
                      resolution(),
                      settings_.bias >= 0.0 ? settings_.bias : 1e-4 * s.diagonal,
                      settings_.slope_bias,
                      settings_.bilinear,
                      colour_texels_.const_view()};
  if (backend == Backend::cuda) trim_device_pool();
  ++generations_;
}

double DeepShadowMaps::generation_milliseconds() const {
  double total = 0.0;
  for (const DsmPass& p : passes_) total += p.milliseconds;
  return total;
}

}  // namespace dv
