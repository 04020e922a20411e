// Every registered strategy of the three families (shadow methods, DSM storages, voxelizers)
// with its description, parameter table and traits (core/strategy_traits.h): what suites expand
// "every storage" from, what advise searches, and what `deepvox list --json` prints for the
// plots. A strategy registered without traits gets its family's fallback (a family of its own,
// searched by advise), so a new strategy reaches all of them from its registration alone.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/param_table.h"
#include "core/strategy_traits.h"

namespace dv {

struct CatalogEntry {
  std::string registry;  // the registry's family: "shadow method", "storage", "voxelizer"
  std::string name;
  std::string description;
  ParamTable params;
  StrategyTraits traits;
  bool traits_declared = false;  // false: the fallback traits
};

// The registries' families, in catalog order.
std::vector<std::string> catalog_registries();
// The strategies of one registry family, by name; InputError naming `where` for an unknown one.
std::vector<CatalogEntry> catalog_of(const std::string& registry, const std::string& where = "");
// Every family's strategies, in catalog_registries() order.
std::vector<CatalogEntry> strategy_catalog();
// The catalog as `deepvox list --json` prints it: {"strategies": [{"registry", "name",
// "description", "family", "colour", "marker", "member_param", "size_key", "sizes",
// "not_advised", "params": [{"key", "type", "default", "range", "description"}]}]}.
nlohmann::json strategy_catalog_json();

}  // namespace dv
