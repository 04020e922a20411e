// One node, several GPUs, no scheduler: `deepvox suite NAME --gpus N|all` starts one worker
// process per GPU (CUDA_VISIBLE_DEVICES=k), or with --backend cpu N processes that share the CPU
// threads, each `deepvox suite ... --shard i/N` into one session folder; shows every worker's
// progress (read from its status file), starts a killed worker again on its shard, and merges
// the shards at the end (merge.h); `--resume` continues a session whose workers were stopped.
#pragma once

#include <string>
#include <vector>

#include "experiments/harness/runner.h"
#include "experiments/harness/suite_file.h"

namespace dv {

// "all" -> the visible GPUs (cuda) or the CPU threads (cpu); a number as is; InputError when
// "all" finds no GPU on cuda or the text is no positive count.
int worker_count(const std::string& gpus, const std::string& backend);

// The arguments of shard `index` of `count` (without the program name): the suite's options,
// --shard, --out, --costs (fixed by the parent so every shard plans alike) and --no-report.
std::vector<std::string> shard_arguments(const SuiteOptions& o, const std::string& suite_path,
                                         int index, int count, const std::string& shards_out,
                                         const std::string& costs);

// The cost source every shard must use: o.costs, or the one item_costs finds now for `suite`
// (the suite file of o.suite, loaded once by the caller).
std::string fixed_cost_source(const SuiteOptions& o, const Suite& suite);

// Runs the workers in a new session folder OUT/<suite>/<date>_<sha>-Nworkers/ (with o.resume:
// the session o.resume_dir, or the newest unmerged one of the suite with `count` workers under
// o.out, each worker resuming its shard's folder) and merges; the merged folder goes to
// o.out/<suite>/. A worker killed by a signal is started again on its shard (at most 3 times).
// Exit code of the worst worker (0, 3 some failed, 130 interrupted: merged with the missing
// items listed); the outcome's folder is the merged one. A shard that did not finish otherwise
// is not merged: ResultWriteError when a worker stopped on a full disk, else InputError or
// Error, naming each shard, its log and the resume command. InputError also for a session that
// cannot be resumed (no session.json, another suite or worker count, options that differ, a
// shard still being written).
SuiteOutcome run_workers(const SuiteOptions& o, int count);

// `deepvox suite NAME --runs N`: N independent process runs of the suite, one after another
// (each a fresh `deepvox suite ... --no-report` child running every item in suite order, so the
// items of a comparison alternate within each round and drift between rounds lands between
// runs). The rounds go to OUT/<suite>/<date>_<sha>-Nruns/<suite>/<date>_<sha>[-k]/ with their
// logs run<k>.log beside; the first round's folder gets runs.json naming the others and the
// report, whose findings' intervals pool the rounds. A round that is interrupted stops the rest.
// With `o.permute` (the replicate protocol) round k orders its items with seed o.order_seed +
// k - 1 (run_order.h) and the session folder's tag says "-replicate".
SuiteOutcome run_rounds(const SuiteOptions& o, int runs);

}  // namespace dv
