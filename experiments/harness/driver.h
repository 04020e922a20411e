// Experiment kinds: a driver runs one RunItem (a scene, a strategy, its parameters) and adds
// measurement rows. Drivers are registered by name (driver_registry); a new kind is one file
// with a register function called from driver_registry(). Drivers build strategies from the
// family registries by name, so a newly registered strategy joins a sweep through the suite
// file alone.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/registry.h"
#include "cuda/execute.h"
#include "experiments/harness/rows.h"
#include "experiments/harness/run_item.h"

namespace dv {

class SceneCache;

// Thrown by a driver when the item cannot run here for a reason that is no failure (a
// voxelizer that does not run on this backend): recorded as a `skipped` row, the suite goes on.
class SkippedRun : public Error {
 public:
  using Error::Error;
};

// What a driver gets besides its item: backend, repetitions, where images go, the per-run
// cache of scenes, probe points and exact answers.
struct RunContext {
  Backend backend = Backend::cpu;
  int repeat = 1;                 // timed repetitions after one warm-up
  std::filesystem::path run_dir;  // images go to run_dir / "images"
  SceneCache* scenes = nullptr;
};

// Adds rows for one item (item, experiment, scene, strategy, params filled in), and its
// per-sample data: every timing repetition and every probe's signed error, which the runner
// writes to samples/<item>.json for the findings' intervals (docs/suite-format.md).
class RowSink {
 public:
  RowSink(const std::string& suite, const RunItem& item, std::vector<Row>& rows)
      : suite_(suite), item_(item), rows_(rows) {}
  void add(const std::string& metric, const std::string& stat, double value,
           const std::string& unit, const std::string& note = "");
  size_t count() const { return added_; }
  // {"timings": {metric: [ms per repetition]}, "probe_errors": {class: [signed error per probe
  // and light]}}; null when the driver adds none.
  nlohmann::json& samples() { return samples_; }

 private:
  const std::string& suite_;
  const RunItem& item_;
  std::vector<Row>& rows_;
  size_t added_ = 0;
  nlohmann::json samples_;
};

class Driver {
 public:
  virtual ~Driver() = default;
  // The settings keys the suite file may give (anything else is rejected at load time).
  virtual std::vector<std::string> settings() const = 0;
  // Report columns when the experiment names none: "metric" or "metric:stat".
  virtual std::vector<std::string> default_columns() const = 0;
  // Runs the item, adds rows; returns the strategy's echoed parameters (params.json). Throws on
  // failure (the runner records the error and goes on).
  virtual nlohmann::json run(const RunItem& item, RunContext& context, RowSink& rows) = 0;
};

Registry<Driver>& driver_registry();
std::vector<std::string> driver_names();
bool driver_accepts_setting(const std::string& kind, const std::string& key);
std::string driver_settings_text(const std::string& kind);

void register_shadow_driver(Registry<Driver>& registry);    // kind "shadow"
void register_voxelize_driver(Registry<Driver>& registry);  // kind "voxelize"

}  // namespace dv
