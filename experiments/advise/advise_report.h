// What `deepvox advise` shows and writes: the probe strata's counts, the Pareto front
// as a table (the worst stratum's p95 and each stratum's, image edge error and RMSE, frame time,
// bytes; the pick and the default marked), the pick's verified error per stratum, the whole
// advice as JSON (every measurement, the front, the pick with its predicted and verified error),
// the pick as a shadow config (shadow_config.h: what render, probe, view and suite files read)
// and a small dependency-free SVG plot of error against frame time (every point, the front
// joined, each stratum's front dashed in its colour, the pick ringed, the bound dashed).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "experiments/advise/advise.h"

namespace dv {

// What the error bound means, in the JSON files.
inline constexpr const char* kAdviseMetric =
    "p95 |T' - T| in every stratum of the probe points (lit, umbra, partial, media; over every "
    "light; the max where a stratum has too few points for a p95)";

// One measurement as JSON ({"ok": false, "failure"} for a failed one).
nlohmann::json measurement_json(const AdviseMeasurement& m);
// The results on the front of one stratum (its judged error against frame time; the results
// whose stratum holds points), by frame time.
std::vector<size_t> stratum_front(const std::vector<AdviseResult>& results, Stratum s);
// "per stratum: lit p95 0 (1800) umbra p95 0.0031 (200) partial max 0.02 (31); worst partial
// 0.02" (max where a stratum has too few points; strata without points left out).
std::string strata_text(const AdviseMeasurement& m);
std::string advice_table(const Advice& advice, const AdviseBudgets& budgets);
nlohmann::json advice_json(const Advice& advice, const AdviseOptions& options);
// The pick's shadow config notes: the scene, the bound, the search's and the verified errors.
nlohmann::json pick_notes(const Advice& advice, const AdviseOptions& options);
std::string advice_svg(const Advice& advice, const AdviseBudgets& budgets);

}  // namespace dv
