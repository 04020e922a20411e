// Shadow method "transmittance-slicemap" (Buchacher 2014 §5.1; lookup in
// transmittance_slicemap_device.h). Per light face: a depth map of the opaque casters (alpha >=
// 1, the shadowmap method's code, depth_maps.h), then a grid of the translucent casters (0 <
// alpha < 1; caster opacities of translucent_casters.h: media boundaries and BLEND textures
// included) over the face's frustum (frustum_grid.h), filled by a registered voxelizer.
// Parameters (table at the registration): voxelizer (voxelizer.KEY passes KEY on to it), slices
// (grid depth), res, pcf, bias, slope (as shadowmap; res is also the grids' columns per side).
// The opacity a of (1 - a)^n is the mean
// over the translucent objects when they differ (stats: casters). Grids and maps are built once
// per scene and backend, never per camera. A voxelizer that cannot run on the backend (exact on
// CUDA) runs on the CPU and its grids are copied; conservative voxelizers (exact, sat) reject
// perspective faces (spot and omni lights) with an InputError (voxel_grid.h).
// Occupancy maps (Sintorn & Assarsson 2009) read such a bit grid per texel the same way; they
// add a fragment count per slab of slices and slices over each texel's own depth range, which
// this method does not have, so `occupancy` is not registered as an alias of it.
#include <map>
#include <memory>
#include <vector>

#include "cuda/pass_timer.h"
#include "engine/raster/fitted_light_faces.h"
#include "strategies/shadow/depth_maps.h"
#include "strategies/shadow/shadow_method.h"
#include "strategies/shadow/translucent_casters.h"
#include "strategies/voxelizer/frustum_grid.h"
#include "strategies/voxelizer/voxelizer.h"

namespace dv {

namespace {

constexpr const char* kName = "transmittance-slicemap";

class TransmittanceSlicemap final : public ShadowMethod {
 public:
  explicit TransmittanceSlicemap(const StrategyParams& p)
      : given_(p),
        params_(DepthMapParams::read(p)),
        slices_(p.integer("slices")),
        voxelizer_(voxelizer_registry().create(p.string("voxelizer"), p.prefixed("voxelizer"))) {}
  std::string name() const override { return kName; }
  nlohmann::json params() const override {
    nlohmann::json j = given_.echo();
    j["voxelizer"] = voxelizer_->name();
    const nlohmann::json voxelizer = voxelizer_->params();
    for (const auto& [key, value] : voxelizer.items()) j["voxelizer." + key] = value;
    return j;
  }
  nlohmann::json stats() const override {
    nlohmann::json j = {{"maps_built", builds_}, {"prepare_calls", prepare_calls_}};
    if (builds_ == 0) return j;
    j["faces"] = faces_;
    j["casters"] = casters_;
    j["set_voxels"] = set_voxels_;
    j["grid_bytes"] = words_.bytes();
    j["opaque_map_bytes"] = opaque_.bytes();
    j["opaque_map_ms"] = opaque_ms_;
    j["voxelize_ms"] = voxelize_ms_;
    j["last_build_ms"] = build_ms_;
    j["voxelizer_passes"] = voxelizer_passes_;
    j["voxelizer_counters"] = voxelizer_counters_;
    j["not_represented"] =
        "interiors of objects (constant media, volumes): cast from their boundaries, with the "
        "medium's opacity across the object's thinnest extent; BLEND texture alpha: the "
        "factor's; translucent casters in one slice of a column count once";
    return j;
  }

  ShadowSourceVariant prepare(const SceneData& scene, Backend backend, const Camera*) override {
    if (prepared_for_ != &scene || backend_ != backend || builds_ == 0) build(scene, backend);
    ++prepare_calls_;
    return source_;
  }
  const std::vector<VoxelGrid>* voxel_grids() const override {
    return builds_ > 0 ? &face_grids_ : nullptr;
  }

 private:
  void build(const SceneData& scene, Backend backend) {
    const SceneView& s = scene.view();
    PassTimer total(backend);
    const LightMapLayout layout = fitted_light_map_layout(
        scene.host_lights(), s.bounds, scene.host_object_bounds(), s.diagonal, params_.res);
    {
      PassTimer timer(backend);
      opaque_ = render_depth_maps(backend, scene, layout, params_.res, DepthCasters::opaque);
      opaque_ms_ = timer.stop();
    }
    const TranslucentCasters casters = gather_translucent_casters(scene);
    casters_ = casters.json();
    build_grids(backend, layout, casters);
    std::vector<double> powers(size_t(slices_) + 1, 1.0);
    for (size_t n = 1; n < powers.size(); ++n)
      powers[n] = powers[n - 1] * (1.0 - casters.alpha_mean);
    const Memory memory = memory_of(backend);
    attenuation_ = Buffer<double>(memory, powers, "transmittance slicemap powers");
    source_ = TransmittanceSlicemapSource{opaque_.source(s, params_), grids_.const_view(),
                                          words_.view(), attenuation_.const_view(), slices_};
    prepared_for_ = &scene;
    backend_ = backend;
    faces_ = int(layout.faces.size());
    ++builds_;
    build_ms_ = total.stop();
  }

  // One grid per face, concatenated in face order; none without translucent casters.
  void build_grids(Backend backend, const LightMapLayout& layout, const TranslucentCasters& c) {
    const Memory memory = memory_of(backend);
    const Backend run_on = voxelizer_->supports(backend) ? backend : Backend::cpu;
    std::vector<GridTransform> transforms;
    std::vector<uint32_t> words;
    std::map<std::string, double> passes;
    voxelizer_counters_ = nlohmann::json::array();
    voxelize_ms_ = 0.0;
    set_voxels_ = 0;
    face_grids_.clear();
    if (c.soup.triangle_count() > 0)
      for (size_t f = 0; f < layout.faces.size(); ++f) {
        const GridSpec spec = make_light_grid(layout.faces[f], params_.res, slices_,
                                              c.soup.bounds(), std::string(kName) + " grid");
        VoxelizeResult r = voxelizer_->voxelize(run_on, c.soup, spec);
        for (const VoxelizePass& p : r.passes) passes[p.name] += p.milliseconds;
        voxelize_ms_ += r.total_milliseconds();
        voxelizer_counters_.push_back(r.counters);
        const std::vector<uint32_t> face_words = r.grid.words();
        words.insert(words.end(), face_words.begin(), face_words.end());
        transforms.push_back(grid_transform(spec));
        face_grids_.push_back(std::move(r.grid));
      }
    for (uint32_t w : words) set_voxels_ += bit_count(w);
    voxelizer_passes_ = nlohmann::json::array();
    for (const auto& [name, ms] : passes) voxelizer_passes_.push_back({{"pass", name}, {"ms", ms}});
    grids_ = Buffer<GridTransform>(memory, transforms, "transmittance slicemap grids");
    words_ = Buffer<uint32_t>(memory, words, "transmittance slicemap words");
  }

  StrategyParams given_;  // resolved: echoes the table's keys
  DepthMapParams params_;
  int slices_;
  std::unique_ptr<Voxelizer> voxelizer_;
  DepthMaps opaque_;
  Buffer<GridTransform> grids_;
  Buffer<uint32_t> words_;
  std::vector<VoxelGrid> face_grids_;  // the voxelizer's grids, kept for inspection
  Buffer<double> attenuation_;
  TransmittanceSlicemapSource source_{};
  const SceneData* prepared_for_ = nullptr;
  Backend backend_ = Backend::cpu;
  int builds_ = 0, prepare_calls_ = 0, faces_ = 0;
  int64_t set_voxels_ = 0;
  double opaque_ms_ = 0.0, voxelize_ms_ = 0.0, build_ms_ = 0.0;
  nlohmann::json casters_, voxelizer_passes_, voxelizer_counters_;
};

}  // namespace

void register_transmittance_slicemap(Registry<ShadowMethod>& registry) {
  registry.add(
      kName,
      "transmittance shadow mapping: opaque depth map (alpha 1, cut per texel by texture "
      "alpha), then (1 - a)^n over a voxel grid of the translucent casters (0 < alpha < 1, "
      "media boundaries included) per light face, Buchacher 2014 5.1",
      join(depth_map_param_table(),
           {name_param("voxelizer", "slicemap",
                       "voxelizer filling the grids of the translucent casters"),
            nested_param("voxelizer", "a parameter of the voxelizer (voxelizer.small=16)"),
            multiple_param("slices", 32, 32, 32, 1024, "depth of each light face's grid")}),
      [](const StrategyParams& p) { return std::make_unique<TransmittanceSlicemap>(p); });
}

}  // namespace dv
