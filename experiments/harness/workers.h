// One node, several GPUs, no scheduler: `deepvox suite NAME --gpus N|all` starts one worker
// process per GPU (CUDA_VISIBLE_DEVICES=k), or with --backend cpu N processes that share the CPU
// threads, each `deepvox suite ... --shard i/N` into one session folder; shows every worker's
// progress (read from its status file) and merges the shards at the end (merge.h).
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

// Runs the workers and merges; the merged folder goes to o.out/<suite>/. Exit code of the
// worst worker (0, 3 some failed, 130 interrupted); the outcome's folder is the merged one.
SuiteOutcome run_workers(const SuiteOptions& o, int count);

// `deepvox suite NAME --runs N`: N independent process runs of the suite, one after another
// (each a fresh `deepvox suite ... --no-report` child running every item in suite order, so the
// items of a comparison alternate within each round and drift between rounds lands between
// runs). The rounds go to OUT/<suite>/<date>_<sha>-Nruns/<suite>/<date>_<sha>[-k]/ with their
// logs run<k>.log beside; the first round's folder gets runs.json naming the others and the
// report, whose findings' intervals pool the rounds. A round that is interrupted stops the rest.
SuiteOutcome run_rounds(const SuiteOptions& o, int runs);

}  // namespace dv
