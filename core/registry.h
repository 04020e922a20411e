// Registries of swappable strategies, one per family (DSM storage, voxelizer, shadow method),
// keyed by case-insensitive name. create() rejects unknown names with the list of known ones and
// rejects parameters the strategy did not read; every strategy echoes its parameters as JSON
// so runs record exactly what ran.
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

  double number(const std::string& key, double fallback) const;
  int integer(const std::string& key, int fallback) const;
  std::string string(const std::string& key, const std::string& fallback) const;
  // A string that must be one of `allowed` (fallback when absent); others are an InputError.
  std::string choice(const std::string& key, const std::string& fallback,
                     const std::vector<std::string>& allowed) const;

  // The parameters "prefix.key" as "key" (marked read here): how a strategy passes parameters
  // on to a strategy of another family it is built from (the dsm method's storage.* keys).
  StrategyParams prefixed(const std::string& prefix) const;

  // Throws InputError naming the strategy and the unread keys.
  void finish(const std::string& strategy) const;

 private:
  std::map<std::string, std::string> values_;
  mutable std::set<std::string> read_;
};

template <class Base>
class Registry {
 public:
  using Factory = std::function<std::unique_ptr<Base>(const StrategyParams&)>;

  explicit Registry(std::string family) : family_(std::move(family)) {}

  // Registering a name twice (in any letter case) is an Error: two strategies cannot share
  // a name.
  void add(const std::string& name, const std::string& description, Factory factory) {
    if (entries_.count(lowercase(name)))
      throw Error(family_ + " '" + name + "' is registered twice");
    entries_[lowercase(name)] = {name, description, std::move(factory)};
  }

  std::unique_ptr<Base> create(const std::string& name, const StrategyParams& params = {}) const {
    auto it = entries_.find(lowercase(name));
    if (it == entries_.end()) {
      std::string known;
      for (const auto& [key, e] : entries_) known += (known.empty() ? "" : ", ") + e.name;
      throw InputError("", family_ + " '" + name + "' not found (known: " +
                               (known.empty() ? "none registered yet" : known) + ")");
    }
    std::unique_ptr<Base> made = it->second.factory(params);
    params.finish(family_ + " '" + name + "'");
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
  const std::string& family() const { return family_; }

 private:
  struct Entry {
    std::string name;
    std::string description;
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
