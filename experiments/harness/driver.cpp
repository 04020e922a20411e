// The registry of experiment kinds and the row sink (driver.h).
#include "experiments/harness/driver.h"

namespace dv {

void RowSink::add(const std::string& metric, const std::string& stat, double value,
                  const std::string& unit, const std::string& note) {
  rows_.push_back({suite_, item_.index, item_.experiment_name, item_.kind, item_.scene,
                   item_.strategy, item_.params_text(), metric, stat, value, unit, note});
  ++added_;
}

Registry<Driver>& driver_registry() {
  static Registry<Driver> registry =
      make_registry<Driver>("experiment kind", {register_shadow_driver, register_voxelize_driver});
  return registry;
}

std::vector<std::string> driver_names() {
  return driver_registry().names();
}

bool driver_accepts_setting(const std::string& kind, const std::string& key) {
  for (const std::string& s : driver_registry().create(kind)->settings())
    if (s == key) return true;
  return false;
}

std::string driver_settings_text(const std::string& kind) {
  std::string out;
  for (const std::string& s : driver_registry().create(kind)->settings())
    out += (out.empty() ? "" : ", ") + s;
  return out;
}

}  // namespace dv
