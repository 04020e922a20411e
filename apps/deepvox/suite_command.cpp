// Which options of `deepvox suite` go together (see suite_command.h).
#include "apps/deepvox/suite_command.h"

#include "core/error.h"

namespace dv::cli {

SuiteMode suite_mode(const SuiteCommand& c) {
  if (c.list) return SuiteMode::list;
  const SuiteOptions& o = c.suite;
  if (o.force && !o.resume) throw InputError("--force", "only with --resume");
  if (o.suite.empty() && !(o.resume && !o.resume_dir.empty()))
    throw InputError("suite", "give a suite name or file (or --list)");
  if (c.runs > 0 && (o.resume || c.use_slurm || !c.gpus.empty() || !o.shard.empty()))
    throw InputError("--runs",
                     "runs the whole suite in one process per run; leave out "
                     "--resume, --slurm, --gpus and --shard");
  if (c.use_slurm) {
    if (c.gpus == "all") throw InputError("--gpus all", "with --slurm give the number of tasks");
    return SuiteMode::slurm;
  }
  if (c.slurm.submit || c.slurm.dry_run || !c.slurm.partition.empty() || !c.slurm.time.empty())
    throw InputError("--submit/--dry-run/--partition/--time", "only with --slurm");
  if (!c.gpus.empty() && !o.shard.empty())
    throw InputError("--gpus", "workers choose their shards; leave out --shard");
  if (c.runs > 0) return SuiteMode::rounds;
  return c.gpus.empty() ? SuiteMode::single : SuiteMode::workers;
}

}  // namespace dv::cli
