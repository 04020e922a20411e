// Which options of `deepvox suite` go together (see suite_command.h).
#include "apps/deepvox/suite_command.h"

#include "core/error.h"

namespace dv::cli {

int round_count(const SuiteCommand& c) {
  return c.runs == 0 && c.protocol == "replicate" ? kReplicateRuns : c.runs;
}

SuiteMode suite_mode(const SuiteCommand& c) {
  if (c.list) return SuiteMode::list;
  const SuiteOptions& o = c.suite;
  if (o.force && !o.resume) throw InputError("--force", "only with --resume");
  if (o.suite.empty() && !(o.resume && !o.resume_dir.empty()))
    throw InputError("suite", "give a suite name or file (or --list)");
  if (!c.protocol.empty() && c.protocol != "replicate")
    throw InputError("--protocol", "expected 'replicate', got '" + c.protocol + "'");
  if (c.protocol == "replicate" && round_count(c) < kReplicateRuns)
    throw InputError("--protocol replicate",
                     "needs at least " + std::to_string(kReplicateRuns) + " runs (--runs)");
  const bool one_folder = o.resume || c.use_slurm || !c.gpus.empty() || !o.shard.empty();
  if (round_count(c) > 0 && one_folder)
    throw InputError(c.protocol.empty() ? "--runs" : "--protocol",
                     "runs the whole suite in one process per run; leave out "
                     "--resume, --slurm, --gpus and --shard");
  if (c.order_seed_given && one_folder)
    throw InputError("--order-seed",
                     "orders the items of one whole run; leave out --resume, --slurm, --gpus "
                     "and --shard");
  if (c.use_slurm) {
    if (c.gpus == "all") throw InputError("--gpus all", "with --slurm give the number of tasks");
    return SuiteMode::slurm;
  }
  if (c.slurm.submit || c.slurm.dry_run || !c.slurm.partition.empty() || !c.slurm.time.empty())
    throw InputError("--submit/--dry-run/--partition/--time", "only with --slurm");
  if (!c.gpus.empty() && !o.shard.empty())
    throw InputError("--gpus", "workers choose their shards; leave out --shard");
  if (round_count(c) > 0) return SuiteMode::rounds;
  return c.gpus.empty() ? SuiteMode::single : SuiteMode::workers;
}

}  // namespace dv::cli
