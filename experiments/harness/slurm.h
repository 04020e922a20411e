// SLURM scale-out without a scheduler of our own: `deepvox suite NAME --slurm` writes one job
// array (task i runs `deepvox suite ... --shard i/N` on one GPU, or one CPU task with
// --backend cpu) and a merge job that runs `deepvox merge` (which writes the report) once every
// task ended (submitted with --dependency=afterany, so a failed shard still leaves a report that
// names it). Array tasks are requeue-safe (--requeue): a task that starts again resumes its
// shard's folder (`--resume`), and one whose deepvox was killed requeues itself (at most 3
// times). --submit hands both to sbatch; the scripts also run by hand (docs/scale-out.md).
// `--slurm --resume [DIR]` hands a session's scripts to sbatch again: its tasks resume their
// shards (a session whose array job was cancelled, timed out or ran out of requeues).
#pragma once

#include <string>

#include "experiments/harness/runner.h"

namespace dv {

struct SlurmOptions {
  int tasks = 1;          // array size (--gpus N); with --resume 0: the session's
  std::string partition;  // empty: the cluster's default
  std::string time;       // e.g. 02:00:00; empty: the partition's default
  bool submit = false;
  bool dry_run = false;
};

struct SlurmScripts {
  std::string folder;        // the session folder (OUT/<suite>/<date>_<sha>-slurm)
  std::string array, merge;  // script texts
};

// The two scripts for a session folder; `exe` is the deepvox binary the jobs run.
SlurmScripts slurm_scripts(const SuiteOptions& o, const SlurmOptions& s, const std::string& folder,
                           const std::string& exe);

// Writes (unless dry_run) FOLDER/slurm/array.sbatch and merge.sbatch, prints them (dry_run) or
// their paths, and with submit runs `sbatch --parsable` on both, the merge job depending on the
// array. With o.resume: the same for the scripts of the session o.resume_dir (else the newest
// of the suite under o.out), written before; InputError when it has none, when an option
// differs from its scripts' or a shard is still being written. Returns the exit code (sbatch
// failures are errors naming the command).
int write_slurm_jobs(const SuiteOptions& o, const SlurmOptions& s);

}  // namespace dv
