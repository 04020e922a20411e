// The calibrated error model behind `--shadows auto --error-budget E`: what the
// accuracy suite measured (the camera-visible p95 of |T' - T|, frame time and bytes of every
// dsm configuration on its scenes), with each calibration scene's statistics as its lights see
// them, versioned in experiments/calibration/error-model.json and regenerated from a suite run
// by `deepvox advise --calibrate RUN_DIR`.
// A light's statistics (light_stats): what its casters are (opaque, translucent, constant
// media, volumes: its kind is the most demanding), how many it reaches (the depth complexity
// along its rays is at most that), and the smallest caster as seen from it (its bounding
// sphere's angle over the light's field: a fraction of a map's side, so texels = fraction x res).
// Prediction (predict_budget): per light, the calibration scenes with a light of the same kind
// answer; a configuration's predicted error is the largest p95 those scenes measured times the
// model's margin. It is confident only when such scenes exist, the light's smallest caster is
// no finer than half the finest those scenes calibrated (finer detail needs more texels than the
// model saw) and some configuration measured on all of them is predicted within E; the pick is
// the cheapest such configuration (mean calibrated frame time) that every light accepts.
// Otherwise the caller measures, as `deepvox advise` does.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/scene/scene_view.h"
#include "strategies/shadow/shadow_config.h"

namespace dv {

inline constexpr const char* kErrorModelFormat = "deepvox-error-model";
// Version 2 adds the metric the configs' errors are (version 1: the camera-visible p95 only).
inline constexpr int kErrorModelVersion = 2;
// The errors a model holds: the stratified error advise judges (probe_strata.h: the worst
// stratum's judged p95), or in older models the camera-visible p95, blind to small shadows.
inline constexpr const char* kStrataMetric = "strata_error:judged";
inline constexpr const char* kVisibleMetric = "probe_error_visible:p95";

enum class LightKind : uint8_t { none, opaque, translucent, media };
const char* to_string(LightKind k);

struct LightStats {
  LightKind kind = LightKind::none;
  int casters = 0, opaque = 0, translucent = 0, media = 0, volumes = 0;
  double smallest_caster = 0.0;  // fraction of the light's field (0: no caster)
  nlohmann::json to_json() const;
  static LightStats from_json(const nlohmann::json& j);
};
std::vector<LightStats> light_stats(const SceneData& scene);

struct CalibratedConfig {
  ShadowConfig shadows;  // a dsm configuration (auto reads the same parameters)
  double p95 = 0.0, frame_ms = 0.0, bytes = 0.0;
};

struct CalibrationScene {
  std::string scene;
  std::vector<LightStats> lights;
  std::vector<CalibratedConfig> configs;
};

struct ErrorModel {
  int version = kErrorModelVersion;
  nlohmann::json source;               // the run it came from: folder, commit, backend, command
  double margin = 1.25;                // predictions are the calibrated error times this
  std::string metric = kStrataMetric;  // what CalibratedConfig::p95 is
  std::vector<CalibrationScene> scenes;
  nlohmann::json to_json() const;
};

// InputError naming the file for a wrong format or a version this build does not read.
ErrorModel read_error_model(const std::string& path);
void write_error_model(const std::string& path, const ErrorModel& model);
// The model built with the deepvox build (experiments/calibration/error-model.json under the
// source tree or the install's share/deepvox): its path, InputError when none is found.
std::string default_error_model_path();

// The model from a suite run folder (rows.csv, meta.json): the dsm items' error (the stratified
// strata_error:judged where the run has it, run with the setting strata_points; else the
// camera-visible p95) and bytes per scene, and their frame time, the median over the folder and
// the further runs its runs.json names (A/A copies left out); the scenes are loaded (resolved as
// the suite resolved them) for their light statistics.
ErrorModel calibrate_error_model(const std::string& run_dir);

struct LightPrediction {
  bool confident = false;
  std::string why;  // plain words: what answered, or why nothing could
  double predicted = 0.0;
};

struct BudgetPrediction {
  bool confident = false;  // every light confident and one configuration meets E on all
  ShadowConfig pick;       // the cheapest such configuration (method auto)
  std::vector<LightPrediction> lights;
  std::string why;
};
BudgetPrediction predict_budget(const ErrorModel& model, const std::vector<LightStats>& lights,
                                double error_budget);

}  // namespace dv
