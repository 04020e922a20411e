// A shadow configuration as a file: a shadow method's name and parameters in JSON,
// what `deepvox advise` writes for its pick and what `render`, `probe` and `view` read with
// --config FILE and a suite file names as a strategy ({"config": FILE}). The "shadows" object
// is a suite file's strategy entry ({"name", "params"}), so it may also be pasted into one.
//   {"format": "deepvox-shadow-config", "version": 1,
//    "shadows": {"name": "dsm", "params": {"storage": "compact", "res": 512, "eps": 0.01}},
//    ...}  (other top-level keys, such as advise's "advice", are the writer's notes)
#pragma once

#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace dv {

inline constexpr const char* kShadowConfigFormat = "deepvox-shadow-config";
inline constexpr int kShadowConfigVersion = 1;

struct ShadowConfig {
  std::string name;                           // a shadow method (shadow_registry())
  std::map<std::string, std::string> params;  // as StrategyParams reads them

  // "key=value" items in key order (what --param takes).
  std::vector<std::string> param_items() const;
  // "--shadows NAME --param k=v ...": the command-line form.
  std::string param_line() const;
  // The file's JSON: format, version and "shadows"; `notes` (an object) adds its keys.
  nlohmann::json to_json(const nlohmann::json& notes = nlohmann::json::object()) const;
};

// Reads a config file: InputError naming the file for a wrong format, a newer version, a
// missing or malformed "shadows" object, an unknown shadow method or parameter.
ShadowConfig read_shadow_config(const std::string& path);
// The same from parsed JSON (`where` names its origin in errors).
ShadowConfig shadow_config_from_json(const nlohmann::json& j, const std::string& where);
// Writes `config.to_json(notes)` to `path` (InputError when it cannot be written).
void write_shadow_config(const std::string& path, const ShadowConfig& config,
                         const nlohmann::json& notes = nlohmann::json::object());

}  // namespace dv
