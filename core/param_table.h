// A strategy's parameters, declared once where it registers: key, type, default, allowed range
// and description. The registry checks given values against them and fills in the defaults
// before the strategy is built (so a strategy reads its keys without fallbacks and has no
// range checks of its own), params() echoes them typed, and `deepvox list` and
// docs/strategies.md print them.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace dv {

struct ParamSpec {
  enum class Type {
    number,   // a finite double in [lo, hi] (bounds open where flagged)
    integer,  // an integer in [lo, hi], a multiple of `step`, or one of `allowed`
    choice,   // one of `allowed`
    name,     // a strategy name of another family, checked by that family's registry
    nested,   // "key.NAME=value" items passed on to that strategy (key is the prefix)
  };
  std::string key;
  Type type = Type::number;
  std::string fallback;  // the default as text; empty: derived by the strategy (see description)
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false, hi_open = false;
  int step = 1;
  std::vector<std::string> allowed;
  std::string description;

  // `value` if it is allowed, else an InputError naming `where` and the key.
  const std::string& check(const std::string& value, const std::string& where) const;
  // The value as JSON of this type (numbers as numbers).
  nlohmann::json typed(const std::string& value) const;
  // "[1, 65536]", "1 | 4 | 9 | 16", "a multiple of 8 in [8, 65536]", "> 0", ...
  std::string range_text() const;
};

// The one number parser of parameter values: true and `v` when `text` is a finite number.
bool parse_param_number(const std::string& text, double& v);
// True when a parsed value is a whole number an int holds (within +-2e9).
bool is_param_integer(double v);
// True when `key` is "prefix.NAME": an item passed on by the nested parameter `prefix`.
bool is_nested_key(const std::string& key, const std::string& prefix);

using ParamTable = std::vector<ParamSpec>;

ParamSpec number_param(std::string key, double fallback, double lo, double hi,
                       std::string description);
// A number greater than 0 (no upper bound).
ParamSpec positive_param(std::string key, double fallback, std::string description);
ParamSpec integer_param(std::string key, int fallback, int lo, int hi, std::string description);
// An integer that is a multiple of `step` in [lo, hi].
ParamSpec multiple_param(std::string key, int fallback, int step, int lo, int hi,
                         std::string description);
// An integer from a short list (e.g. 32 | 64 | 128).
ParamSpec integer_choice_param(std::string key, int fallback, const std::vector<int>& allowed,
                               std::string description);
ParamSpec choice_param(std::string key, std::string fallback, std::vector<std::string> allowed,
                       std::string description);
ParamSpec name_param(std::string key, std::string fallback, std::string description);
ParamSpec nested_param(std::string prefix, std::string description);
// `spec` without a declared default: the strategy derives it (its description says how) and
// reads it with a fallback.
ParamSpec derived(ParamSpec spec);

// Two tables one after the other (a method's own keys after shared ones).
ParamTable join(ParamTable first, const ParamTable& second);

}  // namespace dv
