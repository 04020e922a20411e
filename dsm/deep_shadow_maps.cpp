// DeepShadowMaps (see deep_shadow_maps.h).
#include "dsm/deep_shadow_maps.h"

#include "core/error.h"
#include "cuda/ensure_buffer.h"

namespace dv {

DeepShadowMaps::DeepShadowMaps(DsmSettings settings) : settings_(std::move(settings)) {
  if (settings_.resolution < 1 || settings_.resolution > kMaxRasterSide)
    throw InputError("dsm res", "must lie in [1, 65536]");
  if (!(settings_.eps >= 0.0f)) throw InputError("dsm eps", "must be a number >= 0");
  const int s = settings_.subrays;
  if (s != 1 && s != 4 && s != 9 && s != 16)
    throw InputError("dsm subrays", "must be 1, 4, 9 or 16");
  if (settings_.table_bins < 2 || settings_.table_bins > 1024)
    throw InputError("dsm table_bins", "must lie in [2, 1024]");
  if (!(settings_.step_scale > 0.0)) throw InputError("dsm step_scale", "must be positive");
  if (settings_.clusters.max_clusters < 1) throw InputError("dsm clusters", "must be at least 1");
  if (!(settings_.clusters.d0 >= 0.0)) throw InputError("dsm cluster_d0", "must be >= 0");
  if (!(settings_.clusters.hysteresis >= 0.0))
    throw InputError("dsm cluster_hysteresis", "must be >= 0");
  storage_ = storage_registry().create(settings_.storage, settings_.storage_params);
}

DsmSettings DsmSettings::read(const StrategyParams& p) {
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
  s.clusters.max_clusters = p.integer("clusters", s.clusters.max_clusters);
  s.clusters.d0 = p.number("cluster_d0", s.clusters.d0);
  s.clusters.lispsm = p.choice("lispsm", "0", {"0", "1"}) == "1";
  s.clusters.hysteresis = p.number("cluster_hysteresis", s.clusters.hysteresis);
  return s;
}

nlohmann::json DsmSettings::params(const DsmStorage& created) const {
  nlohmann::json j = {{"storage", created.name()},
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
  const nlohmann::json own = created.params();  // items() must not outlive it
  for (const auto& [key, value] : own.items()) j["storage." + key] = value;
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
    passes_.push_back({"raster", timer.stop()});
  }
  const DsmGenerator& g = generation_->generator();
  ensure_buffer(records_, memory_of(backend), g.texel_count(), "dsm texel records");
  const DsmGenerationContext context{backend, g, settings_.eps, records_.view(), &passes_};
  storage_->generate(context);
  host_records_ = records_.to_vector();
  figures_ = dsm_figures(*storage_, host_records_);
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
                      settings_.bilinear};
  ++generations_;
}

double DeepShadowMaps::generation_milliseconds() const {
  double total = 0.0;
  for (const DsmPass& p : passes_) total += p.milliseconds;
  return total;
}

}  // namespace dv
