// Experiment kind `voxelize`: a voxelizer (any registered name and its parameters) on every
// triangle of a scene, over the scene's bounds made cubic (or the setting `bounds`, the box
// "x0,y0,z0,x1,y1,z1" as `deepvox voxelize --bounds`) at the setting `res` (WxHxD or N).
// Per item: one warm-up and `repeat` timed repetitions, per pass and in total; filled voxels;
// missing and extra voxels against `exact` (also outside the borderline band), the exact grid
// computed once per scene and grid in the run.
#include <map>
#include <tuple>

#include "experiments/harness/driver.h"
#include "experiments/harness/scene_cache.h"
#include "experiments/harness/timing.h"
#include "strategies/voxelizer/voxel_bounds.h"
#include "strategies/voxelizer/voxel_metrics.h"
#include "strategies/voxelizer/voxelizer.h"

namespace dv {

namespace {

class VoxelizeDriver : public Driver {
 public:
  std::vector<std::string> settings() const override { return {"res", "bounds"}; }
  std::vector<std::string> default_columns() const override {
    return {"voxelize_ms:median", "filled", "missing", "extra", "missing_outside_band",
            "extra_outside_band"};
  }

  nlohmann::json run(const RunItem& item, RunContext& ctx, RowSink& rows) override {
    const StrategyParams settings(item.settings);
    const std::string res_text = settings.string("res", "64");
    const std::string bounds_text = settings.string("bounds", "");
    const std::string where = "experiment '" + item.experiment_name + "' setting ";
    settings.finish("experiment '" + item.experiment_name + "' settings");
    const ivec3 res = parse_voxel_resolution(res_text, where + "res");
    const TriangleSoup& soup = soup_of(ctx, item.scene_path);
    const Aabb bounds = bounds_text.empty() ? cubic_bounds(soup.bounds(), item.scene_path)
                                            : parse_voxel_bounds(bounds_text, where + "bounds");
    const GridSpec spec = make_box_grid(res, bounds, item.scene_path);

    auto voxelizer =
        voxelizer_registry().create(item.strategy, StrategyParams::parse(item.param_items()));
    if (!voxelizer->supports(ctx.backend))
      throw SkippedRun("voxelizer '" + item.strategy + "' does not run on the " +
                       to_string(ctx.backend) + " backend");
    PassTimes times;
    VoxelizeResult result;
    for (int rep = 0; rep <= ctx.repeat; ++rep) {
      result = voxelizer->voxelize(ctx.backend, soup, spec);
      if (rep == 0) continue;
      times.add("voxelize", result.total_milliseconds());
      for (const VoxelizePass& p : result.passes) times.add("voxelize." + p.name, p.milliseconds);
    }
    times.emit(rows, "");
    const ExactVoxelization& exact = exact_of(item.scene_path, soup, spec, res, bounds_text);
    const VoxelMetrics m = compare_with_exact(result.grid, exact);
    rows.add("triangles", "value", double(soup.triangle_count()), "count");
    rows.add("voxels", "value", double(spec.voxel_count()), "count");
    rows.add("filled", "value", double(m.filled), "voxels");
    rows.add("exact_filled", "value", double(m.reference_filled), "voxels");
    rows.add("missing", "value", double(m.missing), "voxels");
    rows.add("extra", "value", double(m.extra), "voxels");
    rows.add("borderline", "value", double(m.borderline), "voxels");
    rows.add("missing_outside_band", "value", double(m.missing_outside_band), "voxels");
    rows.add("extra_outside_band", "value", double(m.extra_outside_band), "voxels");
    rows.add("exact_reference_ms", "value", exact.milliseconds, "ms");
    for (const auto& [key, v] : result.counters.items())
      if (v.is_number()) rows.add("counters." + key, "value", v.get<double>(), "");
    return {{"strategy", voxelizer->name()}, {"params", voxelizer->params()}};
  }

 private:
  const TriangleSoup& soup_of(RunContext& ctx, const std::string& path) {
    auto it = soups_.find(path);
    if (it == soups_.end()) it = soups_.emplace(path, triangle_soup(ctx.scenes->scene(path))).first;
    return it->second;
  }
  const ExactVoxelization& exact_of(const std::string& path, const TriangleSoup& soup,
                                    const GridSpec& spec, const ivec3& res,
                                    const std::string& bounds) {
    const auto key = std::make_tuple(path, res.x, res.y, res.z, bounds);
    auto it = exact_.find(key);
    if (it == exact_.end()) it = exact_.emplace(key, voxelize_exact(soup, spec, true)).first;
    return it->second;
  }
  std::map<std::string, TriangleSoup> soups_;
  std::map<std::tuple<std::string, int, int, int, std::string>, ExactVoxelization> exact_;
};

}  // namespace

void register_voxelize_driver(Registry<Driver>& registry) {
  registry.add("voxelize",
               "a voxelizer on a scene's triangles: time per pass, filled voxels, missing and "
               "extra voxels against exact",
               {}, [](const StrategyParams&) { return std::make_unique<VoxelizeDriver>(); });
}

}  // namespace dv
