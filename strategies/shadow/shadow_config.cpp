// Shadow configuration files (shadow_config.h).
#include "strategies/shadow/shadow_config.h"

#include <cmath>
#include <cstdlib>
#include <fstream>

#include "core/error.h"
#include "core/json_reader.h"
#include "strategies/shadow/shadow_method.h"

namespace dv {

std::vector<std::string> ShadowConfig::param_items() const {
  std::vector<std::string> items;
  for (const auto& [key, value] : params) items.push_back(key + "=" + value);
  return items;
}

std::string ShadowConfig::param_line() const {
  std::string line = "--shadows " + name;
  for (const std::string& item : param_items()) line += " --param " + item;
  return line;
}

nlohmann::json ShadowConfig::to_json(const nlohmann::json& notes) const {
  nlohmann::json p = nlohmann::json::object();
  for (const auto& [key, value] : params) {
    // Numbers as numbers, so the file reads as a suite file's params do.
    char* end = nullptr;
    const double number = std::strtod(value.c_str(), &end);
    const bool numeric = !value.empty() && value.find_first_of("xXnN") == std::string::npos &&
                         end && *end == '\0' && std::isfinite(number);
    if (numeric)
      p[key] = value.find_first_of(".eE") == std::string::npos ? nlohmann::json(long(number))
                                                               : nlohmann::json(number);
    else
      p[key] = value;
  }
  nlohmann::json j = {{"format", kShadowConfigFormat},
                      {"version", kShadowConfigVersion},
                      {"shadows", {{"name", name}, {"params", p}}}};
  for (const auto& [key, value] : notes.items()) j[key] = value;
  return j;
}

ShadowConfig shadow_config_from_json(const nlohmann::json& j, const std::string& where) {
  if (!j.is_object()) throw InputError(where, "a shadow config must be a JSON object");
  if (j.value("format", std::string()) != kShadowConfigFormat)
    throw InputError(where, std::string("not a shadow config (\"format\" must be \"") +
                                kShadowConfigFormat + "\")");
  const nlohmann::json version = j.value("version", nlohmann::json());
  if (!version.is_number_integer() || version.get<int>() < 1 ||
      version.get<int>() > kShadowConfigVersion)
    throw InputError(where, "shadow config version " + version.dump() +
                                " is not one this build reads (1.." +
                                std::to_string(kShadowConfigVersion) + ")");
  if (!j.contains("shadows") || !j["shadows"].is_object())
    throw InputError(where, "a shadow config needs a \"shadows\" object {\"name\", \"params\"}");
  JsonReader r(j["shadows"], where, "/shadows");
  ShadowConfig c;
  c.name = r.string("name");
  if (r.has("params")) {
    const nlohmann::json& p = r.raw("params");
    if (!p.is_object()) r.fail("params", "expected an object of key: value");
    for (const auto& [key, value] : p.items()) {
      if (value.is_string())
        c.params[key] = value.get<std::string>();
      else if (value.is_number())
        c.params[key] = value.dump();
      else if (value.is_boolean())
        c.params[key] = value.get<bool>() ? "1" : "0";
      else
        r.fail("params/" + key, "expected a string, number or boolean");
    }
  }
  r.finish();
  try {  // the method and its parameters checked here, so a bad file fails before any work
    shadow_registry().create(c.name, StrategyParams(c.params));
  } catch (const InputError& e) {
    throw InputError(where, e.what());
  }
  return c;
}

ShadowConfig read_shadow_config(const std::string& path) {
  return shadow_config_from_json(parse_json_file(path), path);
}

void write_shadow_config(const std::string& path, const ShadowConfig& config,
                         const nlohmann::json& notes) {
  std::ofstream out(path);
  if (!out) throw InputError(path, "cannot write the shadow config");
  out << config.to_json(notes).dump(2) << "\n";
  if (!out) throw InputError(path, "cannot write the shadow config");
}

}  // namespace dv
