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

double StrategyParams::number(const std::string& key, double fallback) const {
  auto it = values_.find(key);
  if (it == values_.end()) return fallback;
  read_.insert(key);
  char* end = nullptr;
  const double v = std::strtod(it->second.c_str(), &end);
  if (end == it->second.c_str() || *end != '\0' || !std::isfinite(v))
    throw InputError("--param " + key, "expected a number, got '" + it->second + "'");
  return v;
}

int StrategyParams::integer(const std::string& key, int fallback) const {
  const double v = number(key, fallback);
  if (v != std::floor(v) || std::abs(v) > 2e9)
    throw InputError("--param " + key, "expected an integer");
  return int(v);
}

std::string StrategyParams::string(const std::string& key, const std::string& fallback) const {
  auto it = values_.find(key);
  if (it == values_.end()) return fallback;
  read_.insert(key);
  return it->second;
}

std::string StrategyParams::choice(const std::string& key, const std::string& fallback,
                                   const std::vector<std::string>& allowed) const {
  const std::string value = string(key, fallback);
  if (std::find(allowed.begin(), allowed.end(), value) != allowed.end()) return value;
  std::string names;
  for (const std::string& a : allowed) names += (names.empty() ? "'" : ", '") + a + "'";
  throw InputError("--param " + key, "must be one of " + names + ", got '" + value + "'");
}

StrategyParams StrategyParams::prefixed(const std::string& prefix) const {
  std::map<std::string, std::string> inner;
  const std::string head = prefix + ".";
  for (const auto& [key, value] : values_)
    if (key.size() > head.size() && key.compare(0, head.size(), head) == 0) {
      inner[key.substr(head.size())] = value;
      read_.insert(key);
    }
  return StrategyParams(std::move(inner));
}

void StrategyParams::finish(const std::string& strategy) const {
  std::string unknown;
  for (const auto& [key, value] : values_)
    if (!read_.count(key)) unknown += (unknown.empty() ? "'" : ", '") + key + "'";
  if (!unknown.empty()) throw InputError(strategy, "unknown parameter(s) " + unknown);
}

}  // namespace dv
