// Runs a suite: expands it, takes this shard's slice (and --only's), runs every item through
// its driver, records failures and skipped items and goes on, and writes the result folder
// (command.txt, suite.json, meta.json, rows.csv after every item, params.json, images/, report.md).
// Ctrl-C stops after the current item with a report of what was done (exit 130).
#pragma once

#include <string>

namespace dv {

struct SuiteOptions {
  std::string suite;    // built-in name or file
  std::string backend;  // cpu | cuda; empty: the default backend
  std::string out = "out/suites";
  int repeat = 0;           // 0: the suite file's
  std::string shard;        // "I/N"; empty: all
  std::string costs;        // shard balancing (shard_plan.h): "", "estimate" or a result folder
  std::string only;         // substring of experiment name, kind or strategy; empty: all
  bool smoke = false;       // run each experiment's `smoke` form (a CPU-sized correctness run)
  bool progress = true;     // on a terminal only
  bool report = true;       // build report.md (and plots) at the end
  std::string status_file;  // where the progress is written for a parent (workers.h); "": none
};

struct SuiteOutcome {
  int exit_code = 0;  // 0 all ran, 3 some failed, 130 interrupted
  std::string folder;
  int done = 0, total = 0, failed = 0, skipped = 0;
  bool interrupted = false;
};

// InputError for a bad suite file or option (exit 2), before any folder is made.
SuiteOutcome run_suite(const SuiteOptions& options);

// One line per built-in suite: "name  description".
std::string list_suites();

}  // namespace dv
