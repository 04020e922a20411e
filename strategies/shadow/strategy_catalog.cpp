// The strategy catalog (strategy_catalog.h): the three registries read with their traits.
#include "strategies/shadow/strategy_catalog.h"

#include "core/error.h"
#include "strategies/shadow/shadow_method.h"
#include "strategies/storage/dsm_storage.h"
#include "strategies/voxelizer/voxelizer.h"

namespace dv {

const StrategyTraits* shadow_traits(const std::string& name);
const StrategyTraits* storage_traits(const std::string& name);
const StrategyTraits* voxelizer_traits(const std::string& name);

namespace {

template <class Base>
std::vector<CatalogEntry> entries(const Registry<Base>& registry,
                                  const StrategyTraits* (*declared)(const std::string&),
                                  const StrategyTraits& fallback) {
  std::vector<CatalogEntry> out;
  for (const std::string& name : registry.names()) {
    const StrategyTraits* traits = declared(name);
    out.push_back({registry.family(), name, registry.description(name), registry.params(name),
                   traits ? *traits : fallback, traits != nullptr});
  }
  return out;
}

const char* type_name(ParamSpec::Type type) {
  switch (type) {
    case ParamSpec::Type::number:
      return "number";
    case ParamSpec::Type::integer:
      return "integer";
    case ParamSpec::Type::choice:
      return "choice";
    case ParamSpec::Type::name:
      return "name";
    case ParamSpec::Type::nested:
      return "nested";
  }
  return "";
}

}  // namespace

std::vector<std::string> catalog_registries() {
  return {shadow_registry().family(), storage_registry().family(), voxelizer_registry().family()};
}

std::vector<CatalogEntry> catalog_of(const std::string& registry, const std::string& where) {
  if (registry == shadow_registry().family())
    return entries(shadow_registry(), shadow_traits, {"other shadow methods", "#8c564b"});
  if (registry == storage_registry().family())
    return entries(storage_registry(), storage_traits, {"DSM, other storages", "#8c564b"});
  if (registry == voxelizer_registry().family())
    return entries(voxelizer_registry(), voxelizer_traits, {"voxelizers", "#17becf"});
  std::string known;
  for (const std::string& r : catalog_registries()) known += (known.empty() ? "" : ", ") + r;
  throw InputError(where, "unknown strategy family '" + registry + "' (known: " + known + ")");
}

std::vector<CatalogEntry> strategy_catalog() {
  std::vector<CatalogEntry> out;
  for (const std::string& registry : catalog_registries())
    for (CatalogEntry& e : catalog_of(registry)) out.push_back(std::move(e));
  return out;
}

nlohmann::json strategy_catalog_json() {
  nlohmann::json list = nlohmann::json::array();
  for (const CatalogEntry& e : strategy_catalog()) {
    nlohmann::json params = nlohmann::json::array();
    for (const ParamSpec& spec : e.params)
      params.push_back({{"key", spec.key},
                        {"type", type_name(spec.type)},
                        {"default", spec.fallback},
                        {"range", spec.type == ParamSpec::Type::nested ? "" : spec.range_text()},
                        {"description", spec.description}});
    const StrategyTraits& t = e.traits;
    list.push_back({{"registry", e.registry},
                    {"name", e.name},
                    {"description", e.description},
                    {"family", t.family},
                    {"colour", t.colour},
                    {"marker", t.marker},
                    {"member_param", t.member_param},
                    {"size_key", t.size_key},
                    {"sizes", t.sizes},
                    {"not_advised", t.not_advised},
                    {"params", params}});
  }
  return {{"strategies", list}};
}

}  // namespace dv
