// What `deepvox suite` was asked, and which of its options go together, apart from CLI11 so
// that the rules are testable on their own: cmd_suite.cpp fills a SuiteCommand from the command
// line, and suite_mode says which way it runs (or which option does not fit, before any work).
#pragma once

#include <string>

#include "experiments/harness/runner.h"
#include "experiments/harness/slurm.h"

namespace dv::cli {

struct SuiteCommand {
  SuiteOptions suite;             // what the harness runs (suite.resume: --resume was given)
  SlurmOptions slurm;             // --partition, --time, --submit, --dry-run (tasks: from --gpus)
  bool list = false;              // --list
  bool use_slurm = false;         // --slurm
  std::string gpus;               // --gpus N|all; empty: one process
  int runs = 0;                   // --runs N; 0: one run
  std::string protocol;           // --protocol: "replicate" or empty
  bool order_seed_given = false;  // --order-seed S: suite.order_seed (and suite.permute)
};

// The replicate protocol's runs when --runs is not given (and the fewest it accepts).
inline constexpr int kReplicateRuns = 5;

// How many process runs the command asks for: --runs, or kReplicateRuns for --protocol
// replicate without it; 0: one run in this process.
int round_count(const SuiteCommand& command);

enum class SuiteMode {
  list,     // print the built-in suites
  slurm,    // write (and submit) SLURM job scripts
  rounds,   // N independent process runs, one after another (--runs)
  workers,  // one worker process per GPU or CPU slot (--gpus)
  single,   // this process runs the suite (or its --shard)
};

// The way the command runs; InputError naming the option when options do not go together
// (--force without --resume, --runs or --protocol beside --resume/--slurm/--gpus/--shard, a
// protocol other than "replicate" or with fewer than kReplicateRuns runs, --order-seed beside
// --resume/--slurm/--gpus/--shard, a SLURM option without --slurm, --gpus beside --shard, no
// suite).
SuiteMode suite_mode(const SuiteCommand& command);

}  // namespace dv::cli
