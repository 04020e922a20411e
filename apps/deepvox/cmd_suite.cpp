// `deepvox suite` (options: its --help, docs/cli.md; which go together: suite_command.h): runs an
// experiment suite through the harness (experiments/harness/runner.h), continues a killed run
// (--resume; with --gpus a worker session, with --slurm a SLURM session), runs it as worker
// processes on this node (workers.h), as N independent process runs for the findings' intervals
// (--runs, workers.h) or as SLURM jobs (slurm.h), and prints where the report is. Exit codes:
// runner.h (kSuite*), docs/suite-format.md.
#include <cstdio>

#include "apps/deepvox/commands.h"
#include "core/error.h"
#include "experiments/harness/durable_file.h"
#include "experiments/harness/runner.h"
#include "experiments/harness/slurm.h"
#include "experiments/harness/workers.h"

namespace dv::cli {

Runner add_suite(CLI::App& app) {
  auto opt = std::make_shared<SuiteOptions>();
  auto list = std::make_shared<bool>(false);
  auto slurm = std::make_shared<SlurmOptions>();
  auto use_slurm = std::make_shared<bool>(false);
  auto gpus = std::make_shared<std::string>();
  auto runs = std::make_shared<int>(0);
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
  cmd->add_option("--shard", opt->shard,
                  "run shard I of N (items balanced by expected cost, docs/scale-out.md)");
  cmd->add_option("--costs", opt->costs,
                  "shard balancing: a previous result folder's timings or 'estimate' (default: "
                  "the newest whole run of this suite file under --out, else the estimate)");
  cmd->add_option("--gpus", *gpus,
                  "N or 'all': one worker process per GPU (with --backend cpu: N CPU processes), "
                  "merged at the end; with --slurm: the job array's size");
  cmd->add_flag("--slurm", *use_slurm, "write SLURM job scripts (array + merge) under --out");
  cmd->add_option("--partition", slurm->partition, "SLURM partition (with --slurm)");
  cmd->add_option("--time", slurm->time, "SLURM time limit per task, e.g. 02:00:00 (--slurm)");
  cmd->add_flag("--submit", slurm->submit, "submit the SLURM jobs with sbatch (--slurm)");
  cmd->add_flag("--dry-run", slurm->dry_run, "print the SLURM scripts, write nothing (--slurm)");
  cmd->add_option("--status-file", opt->status_file, "progress for a parent process")->group("");
  cmd->add_flag_function(
         "--no-report", [opt](int64_t) { opt->report = false; }, "no report.md")
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
  cmd->add_option("--runs", *runs,
                  "N independent process runs, one after another (at least 3 for intervals "
                  "that hold drift between runs); the report pools them")
      ->check(CLI::PositiveNumber);
  cmd->add_flag("--smoke", opt->smoke,
                "run each experiment's `smoke` form: tiny scenes and sweeps, a CPU correctness "
                "check in seconds, not a measurement");
  return [opt, list, slurm, use_slurm, gpus, resume, runs] {
    if (*list) {
      std::fputs(list_suites().c_str(), stdout);
      return 0;
    }
    opt->resume = resume->count() > 0;
    if (opt->force && !opt->resume) throw InputError("--force", "only with --resume");
    if (opt->suite.empty() && !(opt->resume && !opt->resume_dir.empty()))
      throw InputError("suite", "give a suite name or file (or --list)");
    if (*runs > 0 && (opt->resume || *use_slurm || !gpus->empty() || !opt->shard.empty()))
      throw InputError("--runs",
                       "runs the whole suite in one process per run; leave out "
                       "--resume, --slurm, --gpus and --shard");
    if (*use_slurm) {
      if (*gpus == "all") throw InputError("--gpus all", "with --slurm give the number of tasks");
      slurm->tasks = !gpus->empty() ? worker_count(*gpus, "cpu") : opt->resume ? 0 : 1;
      return write_slurm_jobs(*opt, *slurm);
    }
    if (slurm->submit || slurm->dry_run || !slurm->partition.empty() || !slurm->time.empty())
      throw InputError("--submit/--dry-run/--partition/--time", "only with --slurm");
    if (!gpus->empty() && !opt->shard.empty())
      throw InputError("--gpus", "workers choose their shards; leave out --shard");
    SuiteOutcome r;
    try {
      r = *runs > 0       ? run_rounds(*opt, *runs)
          : gpus->empty() ? run_suite(*opt)
                          : run_workers(*opt, worker_count(*gpus, opt->backend));
    } catch (const ResultWriteError& e) {
      // A full disk or an unwritable folder: the run stopped and resumes (its own exit code).
      std::fprintf(stderr, "deepvox: error: %s\n", e.what());
      return kSuiteStopped;
    }
    if (opt->resume && gpus->empty())
      std::printf("deepvox suite: resumed %s: %d more ran\n", r.folder.c_str(), r.ran_now);
    std::printf("deepvox suite: %s%d of %d experiments, %d failed, %d skipped; %s: %s%s\n",
                r.interrupted ? "interrupted after " : "ran ", r.done, r.total, r.failed, r.skipped,
                opt->report ? "report" : "results", r.folder.c_str(),
                opt->report ? "/report.md" : "");
    return r.exit_code;
  };
}

}  // namespace dv::cli
