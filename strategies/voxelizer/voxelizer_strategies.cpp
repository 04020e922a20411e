// The registered voxelizers `exact` and `sat` (neither takes parameters) and the pass
// bookkeeping of VoxelizeResult.
#include <chrono>
#include <memory>

#include "strategies/voxelizer/exact_voxelizer.h"
#include "strategies/voxelizer/sat_voxelizer.h"
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
  std::string name() const override { return "sat"; }
  nlohmann::json params() const override { return nlohmann::json::object(); }
  bool supports(Backend backend) const override {
    return backend == Backend::cpu || kBuiltWithCuda;
  }
  VoxelizeResult voxelize(Backend backend, const TriangleSoup& soup,
                          const GridSpec& spec) override {
    return voxelize_sat(backend, soup, spec);
  }
};

}  // namespace

void register_exact_voxelizer(Registry<Voxelizer>& registry) {
  registry.add("exact",
               "CPU reference: voxels whose closed box overlaps a triangle (13-axis "
               "separating-axis test, double precision)",
               [](const StrategyParams&) { return std::make_unique<ExactVoxelizer>(); });
}

void register_sat_voxelizer(Registry<Voxelizer>& registry) {
  registry.add("sat",
               "conservative surface voxelization, plane + 2D edge tests (Schwarz & Seidel "
               "2010), CPU and CUDA",
               [](const StrategyParams&) { return std::make_unique<SatVoxelizer>(); });
}

}  // namespace dv
