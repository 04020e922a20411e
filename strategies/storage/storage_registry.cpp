// The DSM storage registry: every storage strategy registers here, once, on first use, and its
// traits (core/strategy_traits.h: plot family, marker, size knob, whether advise searches it)
// stand beside the registration list.
#include <map>

#include "core/strategy_traits.h"
#include "strategies/storage/dsm_storage.h"

namespace dv {

void register_compact_storage(Registry<DsmStorage>& registry);
void register_texture3d_storage(Registry<DsmStorage>& registry);
void register_chunked_storage(Registry<DsmStorage>& registry);
void register_blocked_storage(Registry<DsmStorage>& registry);
void register_beer_storage(Registry<DsmStorage>& registry);
void register_avsm_storage(Registry<DsmStorage>& registry);
void register_moments_storage(Registry<DsmStorage>& registry);
void register_fourier_storage(Registry<DsmStorage>& registry);
void register_occupancy_storage(Registry<DsmStorage>& registry);

Registry<DsmStorage>& storage_registry() {
  static Registry<DsmStorage> registry = make_registry<DsmStorage>(
      "storage", {register_compact_storage, register_texture3d_storage, register_chunked_storage,
                  register_blocked_storage, register_beer_storage, register_avsm_storage,
                  register_moments_storage, register_fourier_storage, register_occupancy_storage});
  return registry;
}

const StrategyTraits* storage_traits(const std::string& name) {
  const std::string node_lists = "DSM, node lists", node_colour = "#ff7f0e";
  const std::string fixed_size = "DSM, fixed-size records", fixed_colour = "#d62728";
  const std::string layout =
      "compact's nodes in another layout, within the same eps: advise searches compact";
  static const std::map<std::string, StrategyTraits> traits{
      {"compact", {node_lists, node_colour, "o"}},
      {"texture3d", {node_lists, node_colour, "s", "", "", {}, layout}},
      {"chunked", {node_lists, node_colour, "^", "", "", {}, layout}},
      {"blocked", {node_lists, node_colour, "D", "", "", {}, layout}},
      {"beer", {fixed_size, fixed_colour, "o"}},
      {"avsm", {fixed_size, fixed_colour, "s", "", "nodes", {"4", "8", "16", "32"}}},
      {"moments", {fixed_size, fixed_colour, "^", "", "moments", {"4", "6"}}},
      {"fourier", {fixed_size, fixed_colour, "D", "", "frequencies", {"4", "8", "16", "32"}}},
      {"occupancy", {fixed_size, fixed_colour, "v", "", "slices", {"32", "64", "128"}}}};
  auto it = traits.find(lowercase(name));
  return it == traits.end() ? nullptr : &it->second;
}

}  // namespace dv
