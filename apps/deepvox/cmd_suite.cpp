// `deepvox suite NAME_OR_FILE [--backend cpu|cuda] [--out DIR] [--repeat K] [--shard I/N]
//  [--only PATTERN] [--smoke]` and `deepvox suite --list`: runs an experiment suite through the
//  harness
// (experiments/harness/runner.h) and prints where the report is.
#include <cstdio>

#include "apps/deepvox/commands.h"
#include "core/error.h"
#include "experiments/harness/runner.h"

namespace dv::cli {

Runner add_suite(CLI::App& app) {
  auto opt = std::make_shared<SuiteOptions>();
  auto list = std::make_shared<bool>(false);
  CLI::App* cmd = app.add_subcommand(
      "suite", "run an experiment suite (built-in name or suite file, docs/suite-format.md)");
  cmd->add_option("suite", opt->suite, "built-in suite name (see --list) or suite file");
  cmd->add_flag("--list", *list, "list the built-in suites");
  cmd->add_option("--backend", opt->backend, "cpu or cuda (default: cuda when a GPU is present)");
  cmd->add_option("--out", opt->out, "results go to OUT/<suite>/<date>_<gitsha>/")
      ->capture_default_str();
  cmd->add_option("--repeat", opt->repeat,
                  "timed repetitions after a warm-up (default: the suite's)")
      ->check(CLI::Range(1, 1000));
  cmd->add_option("--shard", opt->shard, "run shard I of N (items with index % N == I-1)");
  cmd->add_option("--only", opt->only,
                  "only experiments whose name, kind or strategy contains this");
  cmd->add_flag("--smoke", opt->smoke,
                "run each experiment's `smoke` form: tiny scenes and sweeps, a CPU correctness "
                "check in seconds, not a measurement");
  return [opt, list] {
    if (*list) {
      std::fputs(list_suites().c_str(), stdout);
      return 0;
    }
    if (opt->suite.empty()) throw InputError("suite", "give a suite name or file (or --list)");
    const SuiteOutcome r = run_suite(*opt);
    std::printf(
        "deepvox suite: %s%d of %d experiments, %d failed, %d skipped; report: %s/report.md\n",
        r.interrupted ? "interrupted after " : "ran ", r.done, r.total, r.failed, r.skipped,
        r.folder.c_str());
    return r.exit_code;
  };
}

}  // namespace dv::cli
