// Parameter declarations: checking, typed values, range text (see param_table.h).
#include "core/param_table.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>

#include "core/error.h"

namespace dv {

namespace {

// The shortest text that reads back as `v`, as a float where `v` is one (a float setting's
// default 0.02f reads "0.02", not "0.019999999552965164").
std::string number_text(double v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buffer[64];
  const bool is_float = double(float(v)) == v;
  const auto [end, error] = is_float ? std::to_chars(buffer, buffer + sizeof buffer, float(v))
                                     : std::to_chars(buffer, buffer + sizeof buffer, v);
  return error == std::errc() ? std::string(buffer, end) : std::to_string(v);
}

std::string joined(const std::vector<std::string>& items, const char* separator) {
  std::string out;
  for (const std::string& item : items) out += (out.empty() ? "" : separator) + item;
  return out;
}

ParamSpec make(std::string key, ParamSpec::Type type, std::string fallback,
               std::string description) {
  ParamSpec s;
  s.key = std::move(key);
  s.type = type;
  s.fallback = std::move(fallback);
  s.description = std::move(description);
  return s;
}

}  // namespace

bool parse_param_number(const std::string& text, double& v) {
  char* end = nullptr;
  v = std::strtod(text.c_str(), &end);
  return end != text.c_str() && *end == '\0' && std::isfinite(v);
}

bool is_param_integer(double v) {
  return v == std::floor(v) && std::abs(v) <= 2e9;
}

bool is_nested_key(const std::string& key, const std::string& prefix) {
  return key.size() > prefix.size() + 1 && key.compare(0, prefix.size(), prefix) == 0 &&
         key[prefix.size()] == '.';
}

const std::string& ParamSpec::check(const std::string& value, const std::string& where) const {
  const auto fail = [&](const std::string& why) {
    throw InputError(where + " " + key, "must be " + why + ", got '" + value + "'");
  };
  switch (type) {
    case Type::choice:
      if (std::find(allowed.begin(), allowed.end(), value) == allowed.end()) fail(range_text());
      return value;
    case Type::name:
    case Type::nested:
      return value;
    case Type::number:
    case Type::integer:
      break;
  }
  double v = 0.0;
  if (!parse_param_number(value, v)) fail(type == Type::integer ? "an integer" : "a number");
  if (type == Type::integer) {
    if (!is_param_integer(v)) fail("an integer");
    if (!allowed.empty()) {
      if (std::find(allowed.begin(), allowed.end(), number_text(v)) == allowed.end())
        fail(range_text());
      return value;
    }
    if (int64_t(v) % step != 0) fail(range_text());
  }
  const bool below = lo_open ? !(v > lo) : !(v >= lo);
  const bool above = hi_open ? !(v < hi) : !(v <= hi);
  if (below || above) fail(range_text());
  return value;
}

nlohmann::json ParamSpec::typed(const std::string& value) const {
  double v = 0.0;
  if (type == Type::integer && parse_param_number(value, v)) return int64_t(v);
  if (type == Type::number && parse_param_number(value, v)) return v;
  return value;
}

std::string ParamSpec::range_text() const {
  switch (type) {
    case Type::choice:
      return joined(allowed, " | ");
    case Type::name:
      return "a registered name";
    case Type::nested:
      return "any key of that strategy";
    case Type::number:
    case Type::integer:
      break;
  }
  if (!allowed.empty()) return joined(allowed, " | ");
  const bool has_lo = std::isfinite(lo), has_hi = std::isfinite(hi);
  std::string bounds;
  if (has_lo && has_hi) {
    bounds = lo_open ? "(" : "[";
    bounds += number_text(lo) + ", ";
    bounds += number_text(hi);
    bounds += hi_open ? ")" : "]";
  } else if (has_lo)
    bounds = (lo_open ? "> " : ">= ") + number_text(lo);
  else if (has_hi)
    bounds = (hi_open ? "< " : "<= ") + number_text(hi);
  else
    bounds = "any";
  if (step > 1) return "a multiple of " + std::to_string(step) + " in " + bounds;
  std::string text = type == Type::integer ? "an integer " : "";
  text += bounds;
  return text;
}

ParamSpec number_param(std::string key, double fallback, double lo, double hi,
                       std::string description) {
  ParamSpec s =
      make(std::move(key), ParamSpec::Type::number, number_text(fallback), std::move(description));
  s.lo = lo;
  s.hi = hi;
  return s;
}

ParamSpec positive_param(std::string key, double fallback, std::string description) {
  ParamSpec s = number_param(std::move(key), fallback, 0.0, std::numeric_limits<double>::infinity(),
                             std::move(description));
  s.lo_open = true;
  return s;
}

ParamSpec integer_param(std::string key, int fallback, int lo, int hi, std::string description) {
  ParamSpec s = make(std::move(key), ParamSpec::Type::integer, std::to_string(fallback),
                     std::move(description));
  s.lo = lo;
  s.hi = hi;
  return s;
}

ParamSpec multiple_param(std::string key, int fallback, int step, int lo, int hi,
                         std::string description) {
  ParamSpec s = integer_param(std::move(key), fallback, lo, hi, std::move(description));
  s.step = step;
  return s;
}

ParamSpec integer_choice_param(std::string key, int fallback, const std::vector<int>& allowed,
                               std::string description) {
  ParamSpec s = make(std::move(key), ParamSpec::Type::integer, std::to_string(fallback),
                     std::move(description));
  for (int a : allowed) s.allowed.push_back(std::to_string(a));
  return s;
}

ParamSpec choice_param(std::string key, std::string fallback, std::vector<std::string> allowed,
                       std::string description) {
  ParamSpec s =
      make(std::move(key), ParamSpec::Type::choice, std::move(fallback), std::move(description));
  s.allowed = std::move(allowed);
  return s;
}

ParamSpec name_param(std::string key, std::string fallback, std::string description) {
  return make(std::move(key), ParamSpec::Type::name, std::move(fallback), std::move(description));
}

ParamSpec nested_param(std::string prefix, std::string description) {
  return make(std::move(prefix), ParamSpec::Type::nested, "", std::move(description));
}

ParamSpec derived(ParamSpec spec) {
  spec.fallback.clear();
  return spec;
}

ParamTable join(ParamTable first, const ParamTable& second) {
  first.insert(first.end(), second.begin(), second.end());
  return first;
}

}  // namespace dv
