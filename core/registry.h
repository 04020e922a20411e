// Registries of swappable strategies, one per family (DSM storage, voxelizer, shadow method),
// keyed by case-insensitive name. Each strategy registers with its parameter table
// (param_table.h); create() rejects unknown names with the list of known ones, checks the given
// parameters against the table, fills in the defaults and builds the strategy from the result;
// every strategy echoes its parameters (StrategyParams::echo) so runs record exactly what ran.
#pragma once

#include <algorithm>
#include <cctype>
#include <functional>
#include <initializer_list>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/param_table.h"
#include "core/text.h"

namespace dv {

// String parameters given on the command line (--param key=value) or by experiments; strategies
// read them with typed getters, and anything left unread is an error.
class StrategyParams {
 public:
  StrategyParams() = default;
  explicit StrategyParams(std::map<std::string, std::string> values) : values_(std::move(values)) {}

  // Parses "key=value" items.
  static StrategyParams parse(const std::vector<std::string>& items);
  // The items of a JSON object (an echo): strings as they are, numbers as their JSON text.
  static StrategyParams from_json(const nlohmann::json& object);

  // These values checked against `table`, every declared default added: what a strategy is
  // built from. Keys the table does not declare (nor a nested prefix of it) and values out of
  // their range are InputErrors naming `where` and the key. The result keeps `table` (which
  // must outlive it) for echo() and finish().
  StrategyParams resolved(const ParamTable& table, const std::string& where) const;
  // Every declared key with the value given or defaulted, typed as declared; nested keys
  // (storage.KEY) are the nested strategy's to echo.
  nlohmann::json echo() const;

  // A declared key of a resolved object (its default filled in); absent keys are an Error.
  double number(const std::string& key) const;
  int integer(const std::string& key) const;
  std::string string(const std::string& key) const;
  // A key without a declared default (derived by the strategy): `fallback` when absent, and
  // echo() reports the fallback used.
  double number(const std::string& key, double fallback) const;
  int integer(const std::string& key, int fallback) const;
  std::string string(const std::string& key, const std::string& fallback) const;
  // The parameters "prefix.key" as "key" (marked read here): how a strategy passes parameters
  // on to a strategy of another family it is built from (the dsm method's storage.* keys).
  StrategyParams prefixed(const std::string& prefix) const;

  // Throws InputError naming the strategy and the unread keys (an Error for a declared key its
  // strategy never read: the table and the code disagree).
  void finish(const std::string& strategy) const;

 private:
  const std::string* find(const std::string& key) const;

  std::map<std::string, std::string> values_;
  const ParamTable* table_ = nullptr;
  mutable std::set<std::string> read_;
  mutable std::map<std::string, std::string> fallbacks_used_;
};

template <class Base>
class Registry {
 public:
  using Factory = std::function<std::unique_ptr<Base>(const StrategyParams&)>;

  explicit Registry(std::string family) : family_(std::move(family)) {}

  // Registering a name twice (in any letter case) is an Error: two strategies cannot share
  // a name. `params` declares every parameter the factory reads.
  void add(const std::string& name, const std::string& description, ParamTable params,
           Factory factory) {
    if (entries_.count(lowercase(name)))
      throw Error(family_ + " '" + name + "' is registered twice");
    entries_[lowercase(name)] = {name, description, std::move(params), std::move(factory)};
  }

  std::unique_ptr<Base> create(const std::string& name, const StrategyParams& params = {}) const {
    auto it = entries_.find(lowercase(name));
    if (it == entries_.end()) {
      std::string known;
      for (const auto& [key, e] : entries_) known += (known.empty() ? "" : ", ") + e.name;
      throw InputError("", family_ + " '" + name + "' not found (known: " +
                               (known.empty() ? "none registered yet" : known) + ")");
    }
    const std::string where = family_ + " '" + it->second.name + "'";
    const StrategyParams resolved = params.resolved(it->second.params, where);
    std::unique_ptr<Base> made = it->second.factory(resolved);
    resolved.finish(where);
    return made;
  }

  std::vector<std::string> names() const {
    std::vector<std::string> out;
    for (const auto& [key, e] : entries_) out.push_back(e.name);
    return out;
  }
  std::string description(const std::string& name) const {
    auto it = entries_.find(lowercase(name));
    return it == entries_.end() ? "" : it->second.description;
  }
  // The declared parameters of `name` (empty for unknown names).
  const ParamTable& params(const std::string& name) const {
    static const ParamTable none;
    auto it = entries_.find(lowercase(name));
    return it == entries_.end() ? none : it->second.params;
  }
  const std::string& family() const { return family_; }

 private:
  struct Entry {
    std::string name;
    std::string description;
    ParamTable params;
    Factory factory;
  };
  std::string family_;
  std::map<std::string, Entry> entries_;
};

// A family's registry filled by its strategies' registration functions, in order: how each
// family's registry() builds its function-local static on first use.
template <class Base>
Registry<Base> make_registry(std::string family,
                             std::initializer_list<void (*)(Registry<Base>&)> registrations) {
  Registry<Base> registry(std::move(family));
  for (auto add_strategies : registrations) add_strategies(registry);
  return registry;
}

}  // namespace dv
