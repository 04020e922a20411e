// Findings: a paper's claims checked against our rows by a declared comparison. A finding is
// {"claim": text, "lower": [selector, column], "than": [selector, column], "why": text,
// "why_not": text}: the claim holds (confirmed) when the mean of `column` over the items
// matching the first selector is below the mean over the items matching the second. A selector
// is space-separated `key=value` terms that all must hold: `strategy=NAME`, `scene=SUBSTRING`,
// or a parameter (`storage=chunked`); an empty selector matches every item. No match on a side:
// undecided. The explanation is built from the data: the difference and ratio of the two means,
// whether the difference is within the repetitions' spread (a median column: half the mean
// max - min of the two sides), and, for a time column `X_ms`, which of its timed passes
// (`X.*_ms`, the deepest level the rows have) carries the difference and how much lies outside
// them; then the suite's `why` (the mechanism it reads, printed when confirmed) or `why_not`
// (when not confirmed), else "not explained".
#pragma once

#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "experiments/harness/rows.h"

namespace dv {

struct FindingResult {
  std::string claim, why;
  std::string lower_text, than_text;  // "selector: column"
  double lower = 0.0, than = 0.0;     // means over the matching items
  int lower_items = 0, than_items = 0;
  std::string verdict;      // "confirmed", "not confirmed" or "undecided (...)"
  std::string explanation;  // from the data, then the suite's reading (see above)
};

// Whether an item's rows match a selector (see above).
bool selector_matches(const std::string& selector, const Row& first_row_of_item);

// The mean of `column` over the items matching `selector`; `items` counts those that have it.
struct SelectionMean {
  double mean = 0.0;
  int items = 0;
};
SelectionMean selection_mean(const std::string& selector, const Column& column,
                             const std::map<int, std::vector<const Row*>>& items);

// `findings` as validated by the suite loader; `items` the experiment's rows per item.
std::vector<FindingResult> evaluate_findings(const nlohmann::json& findings,
                                             const std::map<int, std::vector<const Row*>>& items);

}  // namespace dv
