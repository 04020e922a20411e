// `--shadows auto --error-budget E`: before the method is made, the auto method's
// parameters are chosen for the scene so that the p95 |T' - T| in every stratum of the probe
// points (experiments/harness/probe_strata.h: lit, umbra, partial, media) stays within E: the
// calibrated error model (experiments/advise/error_model.h) proposes the cheapest
// configuration from the scene's light statistics (caster kinds, how many, the smallest caster
// as the light sees it), and its proposal is measured on the scene's strata at fresh points
// (the model was calibrated on the camera's points alone); when the model cannot predict a
// light or its proposal misses E, the configurations auto takes are measured on the scene as
// `deepvox advise` does (a short search, the pick verified at fresh points; no image bound).
// --explain prints the choice, the strata and the worst one (ShadowOptions::budget_explanation).
#pragma once

#include <string>

#include "apps/common/shadow_options.h"
#include "cuda/execute.h"

namespace dv::cli {

// Sets `options.params` to the chosen configuration (auto's dsm parameters) for the scene file
// `scene_path` rendered on `backend` and clears the budget (resolved); no-op without one.
// InputError when --param or the dsm shortcuts are given beside it (the budget chooses them), or
// when neither the model nor the measurement finds a configuration within E.
void resolve_error_budget(ShadowOptions& options, const std::string& scene_path, Backend backend);

}  // namespace dv::cli
