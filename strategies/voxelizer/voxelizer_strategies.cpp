// The registered voxelizers `exact`, `slicemap` (no parameters), `sat` (parameter small: work
// items of a triangle voxelized by one thread), `atlas` and `atlas-compute` (parameter atlas:
// texels per atlas side), the (empty) registry of GL
// implementations, and the pass bookkeeping of VoxelizeResult.
#include <chrono>
#include <memory>

#include "strategies/voxelizer/atlas_packing.h"
#include "strategies/voxelizer/atlas_voxelizer.h"
#include "strategies/voxelizer/exact_voxelizer.h"
#include "strategies/voxelizer/sat_voxelizer.h"
#include "strategies/voxelizer/slicemap_voxelizer.h"
#include "strategies/voxelizer/voxelizer.h"

namespace dv {

double VoxelizeResult::total_milliseconds() const {
  double total = 0.0;
  for (const VoxelizePass& p : passes) total += p.milliseconds;
  return total;
}

nlohmann::json VoxelizeResult::passes_json() const {
  nlohmann::json out = nlohmann::json::array();
  for (const VoxelizePass& p : passes) out.push_back({{"pass", p.name}, {"ms", p.milliseconds}});
  return out;
}

namespace {

class ExactVoxelizer : public Voxelizer {
 public:
  std::string name() const override { return "exact"; }
  nlohmann::json params() const override { return nlohmann::json::object(); }
  bool supports(Backend backend) const override { return backend == Backend::cpu; }
  VoxelizeResult voxelize(Backend backend, const TriangleSoup& soup,
                          const GridSpec& spec) override {
    if (!supports(backend))
      throw InputError("voxelizer 'exact'", "runs on the CPU only (use --backend cpu)");
    ExactVoxelization exact = voxelize_exact(soup, spec, false);
    VoxelizeResult result;
    result.grid = std::move(exact.exact);
    result.passes.push_back({"voxelize", exact.milliseconds});
    result.counters["triangles"] = soup.triangle_count();
    return result;
  }
};

class SatVoxelizer : public Voxelizer {
 public:
  explicit SatVoxelizer(const StrategyParams& params)
      : small_items_(params.integer("small", int(kSatSmallItems))) {
    validate_sat_small_items(small_items_);
  }
  std::string name() const override { return "sat"; }
  nlohmann::json params() const override { return {{"small", small_items_}}; }
  bool supports(Backend backend) const override {
    return backend == Backend::cpu || kBuiltWithCuda;
  }
  VoxelizeResult voxelize(Backend backend, const TriangleSoup& soup,
                          const GridSpec& spec) override {
    return voxelize_sat(backend, soup, spec, small_items_);
  }

 private:
  int64_t small_items_;
};

class SlicemapVoxelizer : public Voxelizer {
 public:
  std::string name() const override { return "slicemap"; }
  nlohmann::json params() const override { return nlohmann::json::object(); }
  bool supports(Backend backend) const override {
    return backend == Backend::cpu || kBuiltWithCuda;
  }
  VoxelizeResult voxelize(Backend backend, const TriangleSoup& soup,
                          const GridSpec& spec) override {
    return voxelize_slicemap(backend, soup, spec);
  }
};

class AtlasVoxelizer : public Voxelizer {
 public:
  AtlasVoxelizer(bool compute, const StrategyParams& params)
      : compute_(compute), side_(params.integer("atlas", kDefaultAtlasSide)) {
    if (side_ < 1 || side_ > kMaxAtlasSide)
      throw InputError("voxelizer '" + name() + "'",
                       "atlas=" + std::to_string(side_) + " must be in [1, " +
                           std::to_string(kMaxAtlasSide) + "] (texels per atlas side)");
  }
  std::string name() const override { return compute_ ? "atlas-compute" : "atlas"; }
  nlohmann::json params() const override { return {{"atlas", side_}}; }
  bool supports(Backend backend) const override {
    return backend == Backend::cpu || kBuiltWithCuda;
  }
  VoxelizeResult voxelize(Backend backend, const TriangleSoup& soup,
                          const GridSpec& spec) override {
    return compute_ ? voxelize_atlas_compute(backend, soup, spec, side_)
                    : voxelize_atlas(backend, soup, spec, side_);
  }

 private:
  bool compute_;
  int side_;
};

}  // namespace

Registry<Voxelizer>& gl_voxelizer_registry() {
  static Registry<Voxelizer> registry("voxelizer with --backend gl");
  return registry;
}

void register_exact_voxelizer(Registry<Voxelizer>& registry) {
  registry.add("exact",
               "CPU reference: voxels whose closed box overlaps a triangle (13-axis "
               "separating-axis test, double precision)",
               [](const StrategyParams&) { return std::make_unique<ExactVoxelizer>(); });
}

void register_sat_voxelizer(Registry<Voxelizer>& registry) {
  registry.add("sat",
               "conservative surface voxelization, plane + 2D edge tests (Schwarz & Seidel "
               "2010), CPU and CUDA; param small=work items (voxel columns) of a triangle "
               "voxelized by one thread, larger ones split",
               [](const StrategyParams& p) { return std::make_unique<SatVoxelizer>(p); });
}

void register_slicemap_voxelizer(Registry<Voxelizer>& registry) {
  registry.add("slicemap",
               "slices of the fragments rasterized along +z, one bit per fragment (Eisemann & "
               "Decoret 2006), CPU and CUDA; OpenGL with --backend gl",
               [](const StrategyParams&) { return std::make_unique<SlicemapVoxelizer>(); });
}

void register_atlas_voxelizers(Registry<Voxelizer>& registry) {
  registry.add("atlas",
               "one point per texel of a triangle atlas rasterized into a position texture "
               "(Thiedemann et al. 2011), CPU and CUDA; param atlas=texels per side",
               [](const StrategyParams& p) { return std::make_unique<AtlasVoxelizer>(false, p); });
  registry.add("atlas-compute",
               "the atlas points computed and written by a compute kernel, no rasterization "
               "(Buchacher 2014 3.4), CPU and CUDA; param atlas=texels per side",
               [](const StrategyParams& p) { return std::make_unique<AtlasVoxelizer>(true, p); });
}

}  // namespace dv
