// The voxelizer registry (each voxelizer registers itself from its own file: exact, sat,
// slicemap, atlas and atlas-compute) with the voxelizers' traits (core/strategy_traits.h), the
// (empty) registry of GL implementations, and the pass bookkeeping of VoxelizeResult.
#include <map>

#include "core/strategy_traits.h"
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

void register_exact_voxelizer(Registry<Voxelizer>& registry);
void register_sat_voxelizer(Registry<Voxelizer>& registry);
void register_slicemap_voxelizer(Registry<Voxelizer>& registry);
void register_atlas_voxelizers(Registry<Voxelizer>& registry);  // atlas, atlas-compute

Registry<Voxelizer>& voxelizer_registry() {
  static Registry<Voxelizer> registry = make_registry<Voxelizer>(
      "voxelizer", {register_exact_voxelizer, register_sat_voxelizer, register_slicemap_voxelizer,
                    register_atlas_voxelizers});
  return registry;
}

const StrategyTraits* voxelizer_traits(const std::string& name) {
  static const std::map<std::string, StrategyTraits> traits{
      {"exact", {"exact oracle", "black", "*"}},
      {"sat", {"voxelizers", "#17becf", "o"}},
      {"slicemap", {"voxelizers", "#17becf", "s"}},
      {"atlas", {"voxelizers", "#17becf", "^"}},
      {"atlas-compute", {"voxelizers", "#17becf", "D"}}};
  auto it = traits.find(lowercase(name));
  return it == traits.end() ? nullptr : &it->second;
}

Registry<Voxelizer>& gl_voxelizer_registry() {
  static Registry<Voxelizer> registry("voxelizer with --backend gl");
  return registry;
}

}  // namespace dv
