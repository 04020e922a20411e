// DeepShadowMaps (see deep_shadow_maps.h).
#include "strategies/storage/deep_shadow_maps.h"

#include <limits>

#include "core/error.h"
#include "cuda/ensure_buffer.h"
#include "cuda/pass_timer.h"
#include "engine/dsm/dsm_colour.h"

namespace dv {

DeepShadowMaps::DeepShadowMaps(DsmSettings settings) : settings_(std::move(settings)) {
  StrategyParams::from_json(settings_.own_params()).resolved(dsm_param_table(), "dsm");
  storage_ = storage_registry().create(settings_.storage, settings_.storage_params);
}

const ParamTable& dsm_param_table() {
  static const ParamTable table = [] {
    const DsmSettings d;
    const ClusterSettings& c = d.clusters;
    ParamSpec bias = number_param("bias", d.bias, -1.0, std::numeric_limits<double>::infinity(),
                                  "receiver depth bias in world units; < 0: 1e-4 of the scene "
                                  "diagonal");
    return ParamTable{
        name_param("storage", d.storage, "storage strategy of the maps (`deepvox list`)"),
        nested_param("storage", "a parameter of the storage strategy (storage.alloc=thesis)"),
        integer_param("res", d.resolution, 1, kMaxRasterSide, "texels per side of each map"),
        number_param("eps", d.eps, 0.0, std::numeric_limits<double>::infinity(),
                     "bound on the error of every compressed visibility function"),
        choice_param("filter", d.bilinear ? "bilinear" : "none", {"none", "bilinear"},
                     "lookup: nearest texel or bilinear over four"),
        bias,
        number_param("slope", d.slope_bias, 0.0, std::numeric_limits<double>::infinity(),
                     "slope bias: texel sizes times the receiver's tangent to the light"),
        integer_choice_param("subrays", d.subrays, {1, 4, 9, 16},
                             "jittered sub-rays per texel, averaged (pre-filtering)"),
        choice_param("volume", d.precompressed ? "table" : "midpoint", {"midpoint", "table"},
                     "volume steps: midpoint samples, or Hadwiger's pre-compressed tables"),
        integer_param("table_bins", d.table_bins, 2, 1024, "bins of the pre-compressed tables"),
        positive_param("step_scale", d.step_scale, "multiplies the volumes' steps in generation"),
        integer_param("clusters", c.max_clusters, 1, std::numeric_limits<int32_t>::max(),
                      "most clusters per light (Knecht 2011); 1: one map per light face"),
        number_param("cluster_d0", c.d0, 0.0, std::numeric_limits<double>::infinity(),
                     "distance threshold of the clustering, NDC units of the face"),
        integer_choice_param("lispsm", c.lispsm ? 1 : 0, {0, 1},
                             "1: cluster in the light-space perspective of the camera"),
        number_param("cluster_hysteresis", c.hysteresis, 0.0,
                     std::numeric_limits<double>::infinity(),
                     "fraction of cluster_d0 a distance may move before reclustering")};
  }();
  return table;
}

DsmSettings DsmSettings::read(const StrategyParams& p) {
  DsmSettings s;
  s.storage = p.string("storage");
  s.storage_params = p.prefixed("storage");
  s.resolution = p.integer("res");
  s.eps = float(p.number("eps"));
  s.bilinear = p.string("filter") == "bilinear";
  s.bias = p.number("bias");
  s.slope_bias = p.number("slope");
  s.subrays = p.integer("subrays");
  s.precompressed = p.string("volume") == "table";
  s.table_bins = p.integer("table_bins");
  s.step_scale = p.number("step_scale");
  s.clusters.max_clusters = p.integer("clusters");
  s.clusters.d0 = p.number("cluster_d0");
  s.clusters.lispsm = p.integer("lispsm") == 1;
  s.clusters.hysteresis = p.number("cluster_hysteresis");
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
  return {{"storage", storage},
          {"res", resolution},
          {"eps", eps},
          {"filter", bilinear ? "bilinear" : "none"},
          {"bias", bias},
          {"slope", slope_bias},
          {"subrays", subrays},
          {"volume", precompressed ? "table" : "midpoint"},
          {"table_bins", table_bins},
          {"step_scale", step_scale},
          {"clusters", clusters.max_clusters},
          {"cluster_d0", clusters.d0},
          {"lispsm", clusters.lispsm ? 1 : 0},
          {"cluster_hysteresis", clusters.hysteresis}};
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
  ensure_buffer(records_, memory_of(backend), g.texel_count(), "dsm texel records");
  const DsmGenerationContext context{backend, g, settings_.eps, records_.view(), &passes_};
  storage_->generate(context);
  host_records_stale_ = true;
  figures_ = dsm_figures(*storage_, backend, records_.const_view());
  colour_exponents_ = Buffer<vec3>();
  if (scene_tints_light(scene)) {
    PassTimer timer(backend);
    colour_exponents_ = Buffer<vec3>(memory_of(backend), g.texel_count(), "dsm colour exponents");
    generate_colour_exponents(backend, g, colour_exponents_.view());
    passes_.push_back({"colour", timer.stop()});
    const int64_t colour_bytes = colour_exponents_.bytes();
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
                      colour_exponents_.const_view()};
  ++generations_;
}

const std::vector<DsmTexelRecord>& DeepShadowMaps::records() const {
  if (host_records_stale_) {
    host_records_ = records_.to_vector();
    host_records_stale_ = false;
  }
  return host_records_;
}

double DeepShadowMaps::generation_milliseconds() const {
  double total = 0.0;
  for (const DsmPass& p : passes_) total += p.milliseconds;
  return total;
}

}  // namespace dv
