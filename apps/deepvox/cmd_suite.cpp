// `deepvox suite` (options: its --help, docs/cli.md; which go together: suite_command.h): runs an
// experiment suite through the harness (experiments/harness/runner.h), continues a killed run
// (--resume; with --gpus a worker session, with --slurm a SLURM session), runs it as worker
// processes on this node (workers.h), as N independent process runs for the findings' intervals
// (--runs, workers.h; --protocol replicate: at least 5, each in its own item order, run_order.h)
// or as SLURM jobs (slurm.h), and prints where the report is. Exit codes:
// runner.h (kSuite*), docs/suite-format.md.
#include <cstdio>
#include <random>

#include "apps/deepvox/commands.h"
#include "apps/deepvox/suite_command.h"
#include "experiments/harness/durable_file.h"
#include "experiments/harness/workers.h"

namespace dv::cli {

Runner add_suite(CLI::App& app) {
  auto command = std::make_shared<SuiteCommand>();
  SuiteOptions* opt = &command->suite;
  SlurmOptions* slurm = &command->slurm;
  CLI::App* cmd = app.add_subcommand(
      "suite", "run an experiment suite (built-in name or suite file, docs/suite-format.md)");
  cmd->add_option("suite", opt->suite, "built-in suite name (see --list) or suite file");
  cmd->add_flag("--list", command->list, "list the built-in suites");
  cmd->add_option("--backend", opt->backend, "cpu or cuda (default: cuda when a GPU is present)");
  cmd->add_option("--out", opt->out, "results go to OUT/<suite>/<date>_<gitsha>/")
      ->capture_default_str();
  cmd->add_option("--repeat", opt->repeat,
                  "timed repetitions after a warm-up (default: the suite's)")
      ->check(CLI::Range(1, 1000));
  cmd->add_option("--shard", opt->shard,
                  "run shard I of N (items balanced by expected cost, docs/scale-out.md)");
  cmd->add_option("--costs", opt->costs,
                  "shard balancing: a previous result folder's timings or 'estimate' (default: "
                  "the newest whole run of this suite file under --out, else the estimate)");
  cmd->add_option("--gpus", command->gpus,
                  "N or 'all': one worker process per GPU (with --backend cpu: N CPU processes), "
                  "merged at the end; with --slurm: the job array's size");
  cmd->add_flag("--slurm", command->use_slurm,
                "write SLURM job scripts (array + merge) under --out");
  cmd->add_option("--partition", slurm->partition, "SLURM partition (with --slurm)");
  cmd->add_option("--time", slurm->time, "SLURM time limit per task, e.g. 02:00:00 (--slurm)");
  cmd->add_flag("--submit", slurm->submit, "submit the SLURM jobs with sbatch (--slurm)");
  cmd->add_flag("--dry-run", slurm->dry_run, "print the SLURM scripts, write nothing (--slurm)");
  cmd->add_option("--status-file", opt->status_file, "progress for a parent process")->group("");
  cmd->add_flag_function(
         "--no-report", [command](int64_t) { command->suite.report = false; }, "no report.md")
      ->group("");
  cmd->add_option("--only", opt->only,
                  "only experiments whose name, kind or strategy contains this");
  CLI::Option* resume =
      cmd->add_option("--resume", opt->resume_dir,
                      "continue a killed or stopped run in DIR, or without DIR the newest "
                      "unfinished run of this suite (and --shard) under --out: runs only the "
                      "experiments without complete rows; with --gpus N a worker session "
                      "(each worker resumes its shard), with --slurm a SLURM session (its "
                      "scripts again)")
          ->expected(0, 1);
  cmd->add_flag("--force", opt->force,
                "with --resume: continue although the suite file or the deepvox commit differ "
                "from the folder's (meta.json and the report say the run is mixed)");
  cmd->add_option("--runs", command->runs,
                  "N independent process runs, one after another (a verdict needs at least 2; "
                  "the t-intervals over runs narrow with 5 or more); the report pools them")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--protocol", command->protocol,
                  "replicate: at least 5 independent process runs (default 5), each with its "
                  "items in a random order of its own (seed recorded in meta.json) and the two "
                  "sides of every comparison claim measured in adjacent pairs, ABBA; the report "
                  "pools the runs");
  CLI::Option* order_seed =
      cmd->add_option("--order-seed", opt->order_seed,
                      "permute the items with this seed (with --protocol replicate: run k uses "
                      "seed + k - 1; default there: a random seed)");
  cmd->add_flag("--smoke", opt->smoke,
                "run each experiment's `smoke` form: tiny scenes and sweeps, a CPU correctness "
                "check in seconds, not a measurement");
  return [command, resume, order_seed] {
    SuiteOptions& o = command->suite;
    o.resume = resume->count() > 0;
    command->order_seed_given = order_seed->count() > 0;
    o.permute = command->order_seed_given || command->protocol == "replicate";
    if (command->protocol == "replicate" && !command->order_seed_given)
      o.order_seed = (uint64_t(std::random_device{}()) << 32) | std::random_device{}();
    const SuiteMode mode = suite_mode(*command);
    if (mode == SuiteMode::list) {
      std::fputs(list_suites().c_str(), stdout);
      return 0;
    }
    if (mode == SuiteMode::slurm) {
      command->slurm.tasks = !command->gpus.empty() ? worker_count(command->gpus, "cpu")
                             : o.resume             ? 0
                                                    : 1;
      return write_slurm_jobs(o, command->slurm);
    }
    SuiteOutcome r;
    try {
      r = mode == SuiteMode::rounds   ? run_rounds(o, round_count(*command))
          : mode == SuiteMode::single ? run_suite(o)
                                      : run_workers(o, worker_count(command->gpus, o.backend));
    } catch (const ResultWriteError& e) {
      // A full disk or an unwritable folder: the run stopped and resumes (its own exit code).
      std::fprintf(stderr, "deepvox: error: %s\n", e.what());
      return kSuiteStopped;
    }
    if (o.resume && mode == SuiteMode::single)
      std::printf("deepvox suite: resumed %s: %d more ran\n", r.folder.c_str(), r.ran_now);
    std::printf("deepvox suite: %s%d of %d experiments, %d failed, %d skipped; %s: %s%s\n",
                r.interrupted ? "interrupted after " : "ran ", r.done, r.total, r.failed, r.skipped,
                o.report ? "report" : "results", r.folder.c_str(), o.report ? "/report.md" : "");
    return r.exit_code;
  };
}

}  // namespace dv::cli
