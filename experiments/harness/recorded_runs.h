// The independent runs a result folder pools (its runs.json: further process runs of the same
// suite file, paths relative to the folder), for the report's findings, tables and plots and the
// error model's calibration.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "experiments/harness/rows.h"
#include "experiments/harness/run_journal.h"

namespace dv {

// The folders DIR/runs.json names (none without it), each checked to be a run of the suite file
// `suite` with hash `suite_hash`; InputError naming the file or a folder that is not one.
std::vector<std::filesystem::path> recorded_runs(const std::filesystem::path& dir,
                                                 const std::string& suite,
                                                 const std::string& suite_hash);

// Writes DIR/runs.json naming `others` (result folders of the same suite file, independent
// process runs) for the findings' intervals; InputError naming a folder that is not one.
void record_runs(const std::string& dir, const std::vector<std::string>& others);

// The rows the tables and plots show: the first run's, each value the median over the runs of
// that item's row with the same metric and statistic (a timing: the median of the runs'
// medians; values that do not vary between runs stay), and with several runs a timing's min and
// max the lowest and highest of the runs' medians (the run-to-run range) instead of one run's
// repetitions; a loss count (lossy.h) the largest over the runs. With one run its rows.
std::vector<Row> rows_over_runs(const std::vector<RunState>& states);

}  // namespace dv
