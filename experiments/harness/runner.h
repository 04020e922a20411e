// Runs a suite: expands it, takes this shard's slice (and --only's), runs every item through
// its driver, records failures (an out-of-memory one with the bytes asked for) and skipped items
// and goes on, and writes the result folder (command.txt, suite.json, meta.json first, then per
// item its rows and a completion marker, synced: run_journal.h; params.json, images/,
// report.md). Ctrl-C stops after the current item with a report of what was done (exit 130); a
// killed run leaves a folder that `report` reads as partial and `--resume` completes; a full
// disk or unwritable folder stops the run with an error and the folder resumable.
#pragma once

#include <cstdint>
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
  // --resume [DIR]: continue the run in DIR (empty: the newest unfinished one of this suite and
  // shard under `out`), running only the items without complete rows.
  bool resume = false;
  std::string resume_dir;
  bool force = false;  // resume even when the suite file or the commit differ (noted in meta)
  // The replicate protocol's item order (run_order.h) with this seed, recorded in meta.json
  // ("order"); otherwise the suite's order.
  bool permute = false;
  uint64_t order_seed = 0;
};

// Exit codes of `deepvox suite` (docs/suite-format.md, "Exit codes"); an error is 1, bad input
// (a suite file, an option, a folder that cannot be resumed) 2.
inline constexpr int kSuiteDone = 0;
inline constexpr int kSuiteRowsFailed = 3;     // the run ended, some experiments failed
inline constexpr int kSuiteStopped = 4;        // the folder took no more results (full disk)
inline constexpr int kSuiteInterrupted = 130;  // Ctrl-C

struct SuiteOutcome {
  int exit_code = 0;  // kSuiteDone, kSuiteRowsFailed or kSuiteInterrupted
  std::string folder;
  int done = 0, total = 0, failed = 0, skipped = 0;
  int ran_now = 0;  // items run by this call (a resumed run: the rest were there)
  bool interrupted = false;
};

// InputError for a bad suite file or option (exit 2), before any folder is made, and for a
// folder that cannot be resumed (no meta.json, another suite, another suite file or commit
// without `force`, options that differ from the folder's, a run still writing it).
// ResultWriteError (durable_file.h) when the disk is full or the folder unwritable: the run
// stops, what was written stays and resumes (`deepvox suite` exits kSuiteStopped).
SuiteOutcome run_suite(const SuiteOptions& options);

// One line per built-in suite: "name  description".
std::string list_suites();

}  // namespace dv
