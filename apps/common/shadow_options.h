// The shadow-method options `render` and `probe` share: --shadows NAME, --param key=value, and
// the deep-shadow-map shortcuts --storage, --dsm-res, --eps, --filter (the dsm method's
// storage, res, eps and filter parameters; any other method rejects them as unknown) and
// --voxelizer (the transmittance-slicemap method's voxelizer parameter). The default method is
// `auto` (the effect planner); --explain prints its decisions and what the method drops of the
// scene's effects. --config FILE takes the method and its parameters from a shadow config file
// (strategies/shadow/shadow_config.h: what `deepvox advise` writes); --param and the shortcuts
// given beside it override its parameters. --error-budget E asks `auto` for the cheapest
// configuration that keeps the p95 error within E in every stratum of the probe points
// (apps/common/error_budget.h resolves it once the scene is loaded).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "engine/scene/scene.h"
#include "strategies/shadow/shadow_method.h"

namespace dv::cli {

struct ShadowOptions {
  std::string name = "auto";
  std::vector<std::string> params;
  std::string storage, filter, voxelizer;
  // Given or not; the values are checked once, by the method that reads them.
  std::optional<int> dsm_res;
  std::optional<double> eps;
  bool explain = false;  // --explain: print the planner's decisions
  std::string config;    // --config FILE
  std::optional<double> error_budget;
  const CLI::Option* shadows_option = nullptr;  // whether --shadows was given
  // Lines apps/common/error_budget.h adds for --explain: what the budget chose and why.
  std::vector<std::string> budget_explanation;
};

void add_shadow_options(CLI::App* cmd, ShadowOptions& options);
// The method the options name (--error-budget: auto's parameters once
// apps/common/error_budget.h chose them).
std::unique_ptr<ShadowMethod> make_shadow_method(const ShadowOptions& options);
// With --explain, prints the method's last plan in plain words to stdout (headed `label`); a
// method that does not plan says so.
void explain_shadows(const ShadowOptions& options, const ShadowMethod& method,
                     const std::string& label);
// With --explain, prints the effects the scene holds (translucent and glass casters, media,
// volumes, tints) and what the method drops or approximates of each
// (strategies/shadow/effect_losses.h).
void explain_effects(const ShadowOptions& options, const Scene& scene, const ShadowMethod& method);

}  // namespace dv::cli
