// What `deepvox advise` shows and writes (issue 41): the Pareto front as a table (error p95 and
// max at the camera-visible probes, image RMSE, frame time, bytes; the pick marked), the whole
// advice as JSON (every measurement, the front, the pick with its predicted and verified error),
// the pick as a shadow config (shadow_config.h: what render, probe, view and suite files read)
// and a small dependency-free SVG plot of error against frame time (every point, the front
// joined, the pick ringed, the bound dashed).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "experiments/harness/advise.h"

namespace dv {

// One measurement as JSON ({"ok": false, "failure"} for a failed one).
nlohmann::json measurement_json(const AdviseMeasurement& m);
std::string advice_table(const Advice& advice, const AdviseBudgets& budgets);
nlohmann::json advice_json(const Advice& advice, const AdviseOptions& options);
// The pick's shadow config notes: the scene, the bound, the search's and the verified errors.
nlohmann::json pick_notes(const Advice& advice, const AdviseOptions& options);
std::string advice_svg(const Advice& advice, const AdviseBudgets& budgets);

}  // namespace dv
