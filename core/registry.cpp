// StrategyParams parsing and checking (see registry.h).
#include "core/registry.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace dv {

StrategyParams StrategyParams::parse(const std::vector<std::string>& items) {
  std::map<std::string, std::string> values;
  for (const std::string& item : items) {
    const size_t eq = item.find('=');
    if (eq == std::string::npos || eq == 0)
      throw InputError("--param", "expected key=value, got '" + item + "'");
    values[item.substr(0, eq)] = item.substr(eq + 1);
  }
  return StrategyParams(std::move(values));
}

StrategyParams StrategyParams::from_json(const nlohmann::json& object) {
  std::map<std::string, std::string> values;
  for (const auto& [key, value] : object.items())
    values[key] = value.is_string() ? value.get<std::string>() : value.dump();
  return StrategyParams(std::move(values));
}

StrategyParams StrategyParams::resolved(const ParamTable& table, const std::string& where) const {
  const auto declared = [&](const std::string& key) -> const ParamSpec* {
    for (const ParamSpec& spec : table) {
      const bool nested = spec.type == ParamSpec::Type::nested;
      if (!nested && key == spec.key) return &spec;
      if (nested && is_nested_key(key, spec.key)) return &spec;
    }
    return nullptr;
  };
  StrategyParams out;
  out.table_ = &table;
  for (const auto& [key, value] : values_) {
    const ParamSpec* spec = declared(key);
    if (!spec) {
      std::string known;
      for (const ParamSpec& s : table)
        known +=
            (known.empty() ? "" : ", ") + s.key + (s.type == ParamSpec::Type::nested ? ".KEY" : "");
      throw InputError(where, "unknown parameter '" + key + "' (known: " +
                                  (known.empty() ? "none, it takes no parameters" : known) + ")");
    }
    out.values_[key] = spec->check(value, where);
  }
  for (const ParamSpec& spec : table)
    if (spec.type != ParamSpec::Type::nested && !spec.fallback.empty())
      out.values_.emplace(spec.key, spec.fallback);
  return out;
}

nlohmann::json StrategyParams::echo() const {
  nlohmann::json out = nlohmann::json::object();
  if (!table_) return out;
  for (const ParamSpec& spec : *table_) {
    if (spec.type == ParamSpec::Type::nested) continue;
    const std::string* value = find(spec.key);
    if (!value) {
      auto used = fallbacks_used_.find(spec.key);
      if (used == fallbacks_used_.end()) continue;
      value = &used->second;
    }
    out[spec.key] = spec.typed(*value);
  }
  return out;
}

const std::string* StrategyParams::find(const std::string& key) const {
  auto it = values_.find(key);
  if (it == values_.end()) return nullptr;
  read_.insert(key);
  return &it->second;
}

std::string StrategyParams::string(const std::string& key) const {
  const std::string* value = find(key);
  if (!value) throw Error("parameter '" + key + "' has no value: its table declares no default");
  return *value;
}

double StrategyParams::number(const std::string& key) const {
  const std::string value = string(key);
  double v = 0.0;
  if (!parse_param_number(value, v))
    throw InputError("--param " + key, "expected a number, got '" + value + "'");
  return v;
}

int StrategyParams::integer(const std::string& key) const {
  const double v = number(key);
  if (!is_param_integer(v)) throw InputError("--param " + key, "expected an integer");
  return int(v);
}

std::string StrategyParams::string(const std::string& key, const std::string& fallback) const {
  if (find(key)) return string(key);
  fallbacks_used_[key] = fallback;
  return fallback;
}

double StrategyParams::number(const std::string& key, double fallback) const {
  if (find(key)) return number(key);
  fallbacks_used_[key] = nlohmann::json(fallback).dump();
  return fallback;
}

int StrategyParams::integer(const std::string& key, int fallback) const {
  if (find(key)) return integer(key);
  fallbacks_used_[key] = std::to_string(fallback);
  return fallback;
}

StrategyParams StrategyParams::prefixed(const std::string& prefix) const {
  std::map<std::string, std::string> inner;
  for (const auto& [key, value] : values_)
    if (is_nested_key(key, prefix)) {
      inner[key.substr(prefix.size() + 1)] = value;
      read_.insert(key);
    }
  return StrategyParams(std::move(inner));
}

void StrategyParams::finish(const std::string& strategy) const {
  std::string unknown;
  for (const auto& [key, value] : values_) {
    if (read_.count(key)) continue;
    if (table_) throw Error(strategy + " declares parameter '" + key + "' but does not read it");
    unknown += (unknown.empty() ? "'" : ", '") + key + "'";
  }
  if (!unknown.empty()) throw InputError(strategy, "unknown parameter(s) " + unknown);
}

}  // namespace dv
