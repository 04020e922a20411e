// add_shadow_options / make_shadow_method (see shadow_options.h).
#include "apps/common/shadow_options.h"

#include <iostream>

#include "core/error.h"
#include "core/number_text.h"
#include "strategies/shadow/effect_losses.h"
#include "strategies/shadow/effect_planner.h"
#include "strategies/shadow/shadow_config.h"
#include "strategies/storage/dsm_storage.h"

namespace dv::cli {

namespace {

// The dsm method's default for its parameter `key`, as its table declares it (shown by --help).
std::string dsm_default(const std::string& key) {
  for (const ParamSpec& p : shadow_registry().params("dsm"))
    if (p.key == key) return p.fallback;
  return "";
}

}  // namespace

void add_shadow_options(CLI::App* cmd, ShadowOptions& o) {
  o.shadows_option =
      cmd->add_option("--shadows", o.name,
                      "shadow method (see `deepvox list`); auto: per light what its casters need, "
                      "a named method: that method for every light")
          ->capture_default_str();
  cmd->add_option("--config", o.config,
                  "shadow config JSON (what `deepvox advise` writes): its method and parameters; "
                  "--param and the dsm shortcuts override its parameters");
  cmd->add_option("--error-budget", o.error_budget,
                  "auto: the cheapest configuration that keeps the p95 |T' - T| within E in "
                  "every stratum of the probe points (lit, umbra, partial, media): the "
                  "calibrated model's proposal measured on the scene, else measured as advise "
                  "does")
      ->check(CLI::Range(1e-6, 1.0));
  cmd->add_flag("--explain", o.explain,
                "print what the shadow method drops or approximates of the scene's effects and "
                "the planner's decisions (auto: per light method, maps, skips)");
  cmd->add_option("--param", o.params, "shadow-method parameter key=value (repeatable)");
  std::string storages;
  for (const std::string& name : storage_registry().names())
    storages += (storages.empty() ? "" : ", ") + name;
  cmd->add_option("--storage", o.storage, "dsm: storage strategy (" + storages + ")")
      ->default_str(dsm_default("storage"));
  cmd->add_option("--dsm-res", o.dsm_res, "dsm: texels per side of each map (its res parameter)")
      ->default_str(dsm_default("res"));
  cmd->add_option("--eps", o.eps,
                  "dsm: error bound of the compressed visibility functions (its eps parameter)")
      ->default_str(dsm_default("eps"));
  cmd->add_option("--filter", o.filter, "dsm: none or bilinear (its filter parameter)")
      ->default_str(dsm_default("filter"));
  cmd->add_option("--voxelizer", o.voxelizer,
                  "transmittance-slicemap: voxelizer filling its grids (see `deepvox list`)");
}

std::unique_ptr<ShadowMethod> make_shadow_method(const ShadowOptions& o) {
  std::string name = o.name;
  std::vector<std::string> params;
  if (!o.config.empty()) {
    if (o.shadows_option && o.shadows_option->count() > 0)
      throw InputError("--config", "names the method itself; leave --shadows out");
    const ShadowConfig config = read_shadow_config(o.config);
    name = config.name;
    params = config.param_items();
  }
  params.insert(params.end(), o.params.begin(), o.params.end());
  if (!o.storage.empty()) params.push_back("storage=" + o.storage);
  if (o.dsm_res) params.push_back("res=" + std::to_string(*o.dsm_res));
  if (o.eps) params.push_back("eps=" + significant_text(*o.eps, 9));
  if (!o.filter.empty()) params.push_back("filter=" + o.filter);
  if (!o.voxelizer.empty()) params.push_back("voxelizer=" + o.voxelizer);
  return shadow_registry().create(name, StrategyParams::parse(params));
}

}  // namespace dv::cli

namespace dv::cli {

void explain_shadows(const ShadowOptions& o, const ShadowMethod& method, const std::string& label) {
  if (!o.explain) return;
  const nlohmann::json plan = method.plan();
  for (const std::string& line : o.budget_explanation) std::cout << label << ": " << line << "\n";
  std::cout << label << ": ";
  if (plan.is_null())
    std::cout << "shadow method " << method.name()
              << " was named, so it runs for every light (no plan)\n";
  else
    std::cout << "shadow plan\n" << explain_plan(plan);
  std::cout << std::flush;
}

void explain_effects(const ShadowOptions& o, const Scene& scene, const ShadowMethod& method) {
  if (o.explain) std::cout << explain_effects(scene, method.name()) << std::flush;
}

}  // namespace dv::cli
