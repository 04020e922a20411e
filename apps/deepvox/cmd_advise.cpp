// `deepvox advise` (options: its --help, docs/cli.md): the cheapest shadow configuration of the
// user's scene within an error bound in every stratum of its probe points (lit, umbra, partial,
// media) and, unless --speed-only, an image edge error no worse than the default configuration's
// (or --image-error F), measured against the exact oracle (experiments/advise/advise.h): progress
// per measurement on stderr, the Pareto front and the verified pick on stdout, and under DIR
// advice.json (every measurement), pick.json (a shadow config render/probe/view take with --config
// and suite files name), front.svg (error against frame time). Ctrl-C ends the search, keeps what
// was measured and writes the outputs from it (exit 130). With --time it times config files
// alternately, so that drift between them cancels; with --calibrate it regenerates the error model
// of `--shadows auto --error-budget` from an accuracy suite run
// (experiments/advise/error_model.h).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "apps/common/error_budget.h"
#include "apps/deepvox/commands.h"
#include "core/error.h"
#include "core/log.h"
#include "experiments/advise/advise.h"
#include "experiments/advise/advise_report.h"
#include "experiments/advise/error_model.h"
#include "experiments/harness/interrupt.h"
#include "experiments/harness/scene_cache.h"
#include "experiments/harness/timing.h"
#include "strategies/shadow/shadow_config.h"

namespace dv::cli {

namespace {

void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path);
  if (!out || !(out << text)) throw InputError(path.string(), "cannot write");
}

// --auto-budget: the auto method's choice under the budget, measured at the points advise
// verifies with; exit 0 when its p95 there meets the bound, 4 otherwise.
int check_auto_budget(SceneCache& cache, const AdviseOptions& a, Backend backend,
                      const std::filesystem::path& out) {
  ShadowOptions shadows;
  shadows.error_budget = a.budgets.error;
  resolve_error_budget(shadows, a.scene, backend);
  ShadowConfig config{"auto", {}};
  for (const std::string& item : shadows.params) {
    const size_t eq = item.find('=');
    config.params[item.substr(0, eq)] = item.substr(eq + 1);
  }
  AdviseMeasurer measurer(cache, a.scene, a.settings);
  const uint64_t seed = a.settings.seed + kVerifySeedOffset;
  const AdviseMeasurement m = measurer.verify(config, seed);
  for (const std::string& line : shadows.budget_explanation) std::cout << line << "\n";
  std::cout << "auto --error-budget " << a.budgets.error << ": " << config.param_line()
            << "\n  p95 at fresh points (seed " << seed << ") " << m.error_p95 << ", " << m.frame_ms
            << " ms, " << m.bytes / 1e6 << " MB\n  " << (m.ok ? strata_text(m) : m.failure)
            << "\n  fresh points: " << measurer.strata(seed).counts_text() << "\n";
  const nlohmann::json notes = {{"auto_budget",
                                 {{"scene", a.scene},
                                  {"error_budget", a.budgets.error},
                                  {"explanation", shadows.budget_explanation},
                                  {"verified", measurement_json(m)},
                                  {"metric", kAdviseMetric},
                                  {"strata_counts", measurer.strata(seed).counts_text()},
                                  {"verify_seed", seed}}}};
  const nlohmann::json j = config.to_json(notes);
  write_text(out / "auto.json", j.dump(1) + "\n");
  return m.ok && m.error_p95 <= a.budgets.error ? 0 : 4;  // the bound in every stratum
}

// --time: the frame times of config files in interleaved rounds, as advise's final timing takes
// them, so that two configurations are compared in one process and alternately
// (scripts/advise_check.py); timing.json in the output folder; exit 4 when one failed.
int time_configs(SceneCache& cache, const AdviseOptions& a, const std::vector<std::string>& files,
                 const std::filesystem::path& out) {
  std::vector<ShadowConfig> configs;
  for (const std::string& file : files) configs.push_back(read_shadow_config(file));
  AdviseMeasurer measurer(cache, a.scene, a.settings);
  const std::vector<std::vector<double>> times =
      measurer.interleaved_frame_ms(configs, a.final_rounds);
  nlohmann::json j = {{"scene", a.scene},
                      {"image", {measurer.width(), measurer.height()}},
                      {"rounds", a.final_rounds},
                      {"repeat", a.settings.repeat},
                      {"configs", nlohmann::json::array()}};
  bool all_timed = true;
  for (size_t k = 0; k < configs.size(); ++k) {
    const Spread s = spread_of(times[k]);
    all_timed = all_timed && std::isfinite(s.max);
    std::printf("%10.3f ms median (%.3f - %.3f) over %d rounds: %s\n", s.median, s.min, s.max,
                a.final_rounds, configs[k].param_line().c_str());
    j["configs"].push_back({{"file", files[k]},
                            {"param_line", configs[k].param_line()},
                            {"times_ms", times[k]},
                            {"median_ms", s.median},
                            {"min_ms", s.min},
                            {"max_ms", s.max}});
  }
  write_text(out / "timing.json", j.dump(1) + "\n");
  return all_timed ? 0 : 4;
}

}  // namespace

Runner add_advise(CLI::App& app) {
  struct Options {
    std::string scene, backend, out, calibrate, model_out;
    double error = 0.02;
    std::optional<double> budget_ms, memory_mb, image_error;
    AdviseSettings settings;
    int max_evaluations = 60, max_res = 0, rounds = 5;
    bool exhaustive = false, auto_budget = false, speed_only = false;
    std::vector<std::string> time_configs;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "advise",
      "the cheapest shadow configuration of a scene within an error bound, measured against "
      "the exact oracle: Pareto front, verified pick, config file, plot");
  cmd->add_option("scene", opt->scene, "scene: .json, .gltf/.glb or a mesh file");
  cmd->add_option("--error", opt->error,
                  "bound on the p95 |T' - T| in every stratum of the probe points (lit, umbra, "
                  "partial, media: camera-visible first, then each light's view of the "
                  "receivers; the max where a stratum has too few points)")
      ->check(CLI::Range(1e-6, 1.0))
      ->capture_default_str();
  cmd->add_option("--image-error", opt->image_error,
                  "bound on the image edge error against the reference render (default: the "
                  "default configuration's, measured too)")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_flag("--speed-only", opt->speed_only,
                "no image bound: the cheapest within --error and the budgets, its image edge "
                "error whatever it is");
  cmd->add_option("--budget-ms", opt->budget_ms, "most frame time (generation + render), ms")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--memory-mb", opt->memory_mb, "most bytes of the shadow method, MB (1e6)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--backend", opt->backend, "cpu or cuda (default: cuda when a GPU is present)");
  cmd->add_option("--out", opt->out,
                  "folder for advice.json, pick.json and front.svg (default: advise-<scene>)");
  cmd->add_option("--width", opt->settings.width,
                  "image width of the measurements (default: the camera's, at most 320)")
      ->check(CLI::Range(1, 16384));
  cmd->add_option("--height", opt->settings.height,
                  "image height (default: the camera's aspect at that width)")
      ->check(CLI::Range(1, 16384));
  cmd->add_option("--probes", opt->settings.probes,
                  "camera-visible probe points (and as many inside media)")
      ->check(CLI::Range(10, 1000000))
      ->capture_default_str();
  cmd->add_option("--stratum-min", opt->settings.stratum_min,
                  "probe samples wanted per surface stratum (lit, umbra, partial) for its p95")
      ->check(CLI::Range(20, 1000000))
      ->capture_default_str();
  cmd->add_option("--repeat", opt->settings.repeat, "timed repetitions after a warm-up")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  cmd->add_option("--max-evaluations", opt->max_evaluations,
                  "most configurations the search measures before its pick is verified; each "
                  "round whose candidates the fresh points reject measures up to " +
                      std::to_string(kResumeEvaluations) + " more, " +
                      std::to_string(kResumedRounds) + " rounds at most")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  cmd->add_flag("--exhaustive", opt->exhaustive,
                "measure every configuration of the space (the search's check), not a search");
  cmd->add_option("--max-res", opt->max_res,
                  "no map resolution above this (small machines; default: the space's 2048)")
      ->check(CLI::Range(16, 16384));
  cmd->add_flag("--auto-budget", opt->auto_budget,
                "instead of a search: what `--shadows auto --error-budget E` (E: --error) "
                "chooses on the scene and why, measured at fresh points (auto.json)");
  cmd->add_option("--rounds", opt->rounds,
                  "interleaved rounds in which the cheapest candidates (within 1.5x of the "
                  "cheapest's time, at most 6) are timed again before the pick (and of --time)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  cmd->add_option("--time", opt->time_configs,
                  "instead of a search: the frame times of these shadow config files (as "
                  "--config takes) in --rounds interleaved rounds (timing.json)");
  cmd->add_option("--calibrate", opt->calibrate,
                  "regenerate the error model of --error-budget from an accuracy suite run "
                  "folder (rows.csv) instead of advising");
  cmd->add_option("--model-out", opt->model_out,
                  "--calibrate: where the model goes (default: the build's "
                  "experiments/calibration/error-model.json)");
  return [opt] {
    namespace fs = std::filesystem;
    if (!opt->calibrate.empty()) {
      const ErrorModel model = calibrate_error_model(opt->calibrate);
      const std::string path = opt->model_out.empty() ? default_error_model_path() : opt->model_out;
      write_error_model(path, model);
      log_info("advise: error model from " + opt->calibrate + " (" +
               std::to_string(model.scenes.size()) + " scenes) -> " + path);
      return 0;
    }
    if (opt->scene.empty()) throw InputError("advise", "name a scene (or --calibrate RUN_DIR)");
    const Backend backend = opt->backend.empty() ? default_backend() : parse_backend(opt->backend);
    require_backend(backend);
    AdviseOptions a;
    a.scene = opt->scene;
    a.budgets.error = opt->error;
    a.budgets.frame_ms = opt->budget_ms;
    a.budgets.image_error = opt->image_error;
    a.speed_only = opt->speed_only;
    if (opt->memory_mb) a.budgets.bytes = *opt->memory_mb * 1e6;
    a.settings = opt->settings;
    a.max_evaluations = opt->max_evaluations;
    a.exhaustive = opt->exhaustive;
    a.max_res = opt->max_res;
    a.final_rounds = opt->rounds;
    a.progress = [](const std::string& line) {
      std::fprintf(stderr, "advise: %s\n", line.c_str());
    };
    const fs::path out = opt->out.empty()
                             ? fs::path("advise-" + fs::path(opt->scene).stem().string())
                             : fs::path(opt->out);
    std::error_code ec;
    fs::create_directories(out, ec);
    if (ec) throw InputError(out.string(), "cannot create the output folder: " + ec.message());
    SceneCache cache(backend);
    if (opt->auto_budget) return check_auto_budget(cache, a, backend, out);
    if (!opt->time_configs.empty()) return time_configs(cache, a, opt->time_configs, out);
    Advice advice;
    {
      InterruptScope interrupts;  // Ctrl-C: the search stops, what was measured is kept
      advice = advise(cache, a);
    }
    std::cout << advice_table(advice, advice.budgets);
    write_text(out / "advice.json", advice_json(advice, a).dump(1) + "\n");
    write_text(out / "front.svg", advice_svg(advice, advice.budgets));
    if (advice.pick) {
      const ShadowConfig& pick = advice.results[*advice.pick].config;
      write_shadow_config((out / "pick.json").string(), pick, pick_notes(advice, a));
      std::cout << "param line: " << pick.param_line()
                << "\nconfig: " << (out / "pick.json").string()
                << " (render/probe/view --config FILE)\n";
    }
    log_info("advise: " + std::to_string(advice.results.size()) + " configurations in " +
             std::to_string(advice.seconds) + " s on " + to_string(backend) + " -> " +
             out.string());
    if (advice.interrupted) return 130;
    return advice.pick ? 0 : 4;
  };
}

}  // namespace dv::cli
