// Resolving --error-budget for the auto method (error_budget.h).
#include "apps/common/error_budget.h"

#include "core/error.h"
#include "core/log.h"
#include "core/number_text.h"
#include "experiments/advise/advise.h"
#include "experiments/advise/advise_report.h"
#include "experiments/advise/error_model.h"
#include "experiments/harness/scene_cache.h"

namespace dv::cli {

namespace {

// The measured fallback: an advise search over what auto takes, as long as advise's own (a
// shorter one can stop before the resolutions a tight budget needs: knecht-fig56 within 0.005
// needs res 1024), with fewer probe points.
constexpr int kFallbackProbes = 1000;

}  // namespace

void resolve_error_budget(ShadowOptions& o, const std::string& scene_path, Backend backend) {
  if (!o.error_budget) return;
  if (!o.params.empty() || !o.storage.empty() || o.dsm_res || o.eps || !o.filter.empty() ||
      !o.config.empty())
    throw InputError("--error-budget",
                     "chooses the parameters itself; leave --param, --config and the dsm "
                     "shortcuts out");
  if (o.name != "auto")
    throw InputError("--error-budget",
                     "only the auto method takes an error budget (got " + o.name + ")");
  const double budget = *o.error_budget;
  SceneCache cache(backend);
  const std::vector<LightStats> stats = light_stats(cache.host_data(scene_path));
  const ErrorModel model = read_error_model(default_error_model_path());
  const BudgetPrediction p = predict_budget(model, stats, budget);
  std::vector<std::string>& why = o.budget_explanation;
  why.push_back("error budget " + significant_text(budget, 4) +
                " (p95 |T' - T| in every stratum of the probe points: lit, umbra, partial, "
                "media)");
  for (size_t l = 0; l < stats.size(); ++l)
    why.push_back(
        "  light " + std::to_string(l) + " (" + to_string(stats[l].kind) + ", " +
        std::to_string(stats[l].casters) + " casters, smallest " +
        significant_text(stats[l].smallest_caster, 4) + " of its field): " + p.lights[l].why +
        (p.confident ? ", predicted p95 " + significant_text(p.lights[l].predicted, 4) : ""));
  o.error_budget.reset();  // resolved: the viewer may switch methods freely afterwards
  AdviseOptions a;         // advise's own limits: as many evaluations as its search
  a.scene = scene_path;
  a.budgets.error = budget;
  a.settings.probes = kFallbackProbes;
  a.auto_only = true;
  a.speed_only = true;  // the budget is the probe error's; the image bound is advise's
  if (p.confident) {
    // The model was calibrated on the camera's points alone, which miss shadows that cover
    // little of the view: its pick is taken when it meets E in every stratum at fresh points.
    AdviseSettings check = a.settings;
    check.repeat = 1;
    AdviseMeasurer measurer(cache, scene_path, check);
    const ShadowConfig& config = p.pick;
    const uint64_t seed = check.seed + kVerifySeedOffset;
    const AdviseMeasurement m = measurer.verify(config, seed);
    why.push_back("model (" + model.source.value("run", std::string("?")) + "): " + p.why + ": " +
                  p.pick.param_line());
    why.push_back("  measured at fresh points (" + measurer.strata(seed).counts_text() +
                  "): " + (m.ok ? strata_text(m) : "failed: " + m.failure));
    if (m.ok && m.error_p95 <= budget) {
      o.params = p.pick.param_items();
      return;
    }
    why.push_back(
        "model's pick misses the budget on this scene; measuring as `deepvox advise` "
        "does");
  } else {
    why.push_back("model: " + p.why + "; measuring on the scene as `deepvox advise` does");
  }
  log_info("--error-budget: measuring on the scene (" + std::to_string(a.max_evaluations) +
           " configurations at most)");
  const Advice advice = advise(cache, a);
  why.push_back("  probe strata: " + advice.strata_counts);
  if (!advice.pick)
    throw InputError("--error-budget", "no configuration of auto measured within " +
                                           significant_text(budget, 4) + " on " + scene_path +
                                           " (run `deepvox advise` for the front)");
  const AdviseResult& pick = advice.results[*advice.pick];
  o.params = pick.config.param_items();
  why.push_back("measured " + std::to_string(advice.results.size()) +
                " configurations: the cheapest within the budget, " + pick.config.param_line() +
                ", p95 " + significant_text(pick.measurement.error_p95, 4) + " (verified " +
                significant_text(advice.verified.error_p95, 4) + " at fresh points), " +
                significant_text(advice.chosen_ms(*advice.pick), 4) + " ms");
  why.push_back("  verified " + strata_text(advice.verified));
}

}  // namespace dv::cli
