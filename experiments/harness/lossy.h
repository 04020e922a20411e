// Lossy rows: an item whose measurement lost data, because a fixed-size structure overflowed
// (a storage's nodes merged or recompressed past its capacity, nodes a chunked pool refused, a
// walk's fixed buffer full) or something was dropped. Its error then includes the loss, so every
// place that prints the row marks it (kLossyMark, docs/suite-format.md "Lossy rows"): the
// experiment tables, the paper tables' "ours", the Pareto fronts, the image strip and the plots
// (plot_suite.py's is_lossy reads the same metric names); the findings call such an item a
// defect unless the claim expects the loss.
#pragma once

#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "experiments/harness/findings.h"
#include "experiments/harness/rows.h"

namespace dv {

// The mark after a lossy item's label, and what it means in one sentence.
inline constexpr const char* kLossyMark = " †";
inline constexpr const char* kLossyMeaning =
    "† lossy: in at least one run a fixed-size structure overflowed (storage nodes merged, "
    "recompressed or refused past its capacity, or a walk's buffer full), so the item's error "
    "includes that loss";

// Whether `metric` counts a loss: its name holds "overflow" or "dropped".
bool is_loss_metric(const std::string& metric);

// "stats.storage.overflowed_texels = 8816, stats.storage.overflow_max_error = 1": the item's
// rows with a loss metric above 0, each metric once; empty when there is none.
std::string loss_text(const std::vector<const Row*>& rows);

// Per lossy item of `runs`: the loss text of the first run in which it lost data.
std::map<int, std::string> lossy_items(const std::vector<RunView>& runs);

// Whether a cell of a table's body ends with kLossyMark (the table then needs its legend).
bool body_has_mark(const std::vector<std::vector<std::string>>& body);

// Under an experiment's table: kLossyMeaning, then each of `items` that is lossy with its
// losses ("- item 12 (dsm res=512 storage=avsm): stats.storage.overflowed_texels = 4957");
// nothing when none is.
void write_lossy_list(std::ostream& md, const std::map<int, std::vector<const Row*>>& items,
                      const std::map<int, std::string>& lossy);

}  // namespace dv
