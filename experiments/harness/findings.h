// Findings: a paper's claims checked against our rows with an effect size and its 95 % interval
// (effect_interval.h). Two forms (docs/suite-format.md, "Findings"):
// - a comparison {"claim", "lower": [selector, column], "than": [selector, column], "why",
//   "why_not"}: the first side's items measure lower than the second's. The effect: for probe
//   error columns (probe_error_<class>:mean|max|p99) the difference of the sides' means, with a
//   paired bootstrap over the probe points (samples/<item>.json of the first run); for every
//   other column the ratio of the sides' means (first / second), with a Student-t interval over
//   the per-run ratios on the log scale (timings from samples/<item>.json, a run's mean over its
//   repetitions; other values one per run, from rows.csv); fewer than 2 runs give no verdict.
// - a trend {"claim", "trend": "increasing"|"decreasing"|"plateau", "over": KEY, "selector",
//   "column", "levels" (optional), "from" (plateau), "why", "why_not"}: the items matching
//   `selector` grouped by the value of KEY (a parameter, or "scene" with `levels` naming
//   substrings of the scene paths, in order); every consecutive step is a comparison of level
//   k+1 against level k. Increasing / decreasing: every step's interval above / below "no
//   effect"; plateau: every step from the level `from` on (default: the second level) contains
//   "no effect".
// Verdicts: "confirmed" (the interval entirely on the claimed side; every step for a monotone
// trend), "refuted" (entirely on the other side; a step of a trend against it, or a plateau step
// that moves), "tie" (the interval contains "no effect", whatever the claim: a plateau whose
// every step holds no effect is a tie, as it claims, never "confirmed"; for differences "no
// effect" is the suite's practical band of the metric), "not comparable (...)" (a side without
// items, units that differ, no row carries the claim's timer, 0 against 0 (both sides measure 0:
// a count that stays 0 says nothing about the claim), no samples to build an interval: a folder
// from before samples/, or fewer than 2 runs), "defect (...)" (an item of a side has a row
// whose metric names an "overflow" or "dropped" count above 0: its measurement lost data),
// "cannot be tested as the paper did: REASON (ours: VERDICT)" (the claim's "not_as_paper": our
// rows lack the paper's timer or baseline). Every claim names its "timer": the time metric that
// decides it (generate_ms, a pass such as generate.passes.count_ms, frame_ms) or "none" for a
// quantity no timer measures (bytes, layers, errors), printed beside the verdict. A selector is
// space-separated `key=value` terms that all must hold: `strategy=NAME`, `scene=SUBSTRING`,
// `experiment=NAME`, or a parameter (`storage=chunked`); an empty selector matches every item. The
// explanation is built from the data (difference and ratio of the means and, for a time column
// `X_ms`, which of its timed passes `X.*_ms` carries the difference), then the suite's `why`
// (confirmed) or `why_not`.
#pragma once

#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "experiments/harness/effect_interval.h"
#include "experiments/harness/rows.h"

namespace dv {

// One independent process run of a suite, as the findings read it: rows per item and the
// item's samples (samples/<item>.json; absent for items, or whole folders, without them).
struct RunView {
  std::map<int, std::vector<const Row*>> items;
  std::map<int, nlohmann::json> samples;
};

// One comparison of two selections of items.
struct Comparison {
  std::string verdict;  // "confirmed" (first below second), "refuted", "tie", "not comparable
                        // (...)", "defect (...)"
  // Means over the items: of every sample of every run where the interval rests on samples,
  // else of the first run's rows.
  double first = 0.0, second = 0.0;
  int first_items = 0, second_items = 0;
  bool has_interval = false;
  EffectInterval interval;
  std::string basis;  // what the interval rests on: runs, repetitions, probe points, items
};

struct TrendStep {
  std::string from, to;   // levels
  Comparison comparison;  // `to` against `from`
};

struct FindingResult {
  std::string claim, why;
  std::string lower_text, than_text;  // "selector: column"; a trend: "selector: column over KEY"
  double lower = 0.0, than = 0.0;     // means over the matching items (comparisons)
  int lower_items = 0, than_items = 0;
  std::string verdict;
  std::string effect;  // "0.61x [0.58, 0.64]" or the trend's steps
  std::string basis;
  std::vector<TrendStep> steps;  // trends
  std::string explanation;       // from the data, then the suite's reading
  std::string timer;             // the claim's "timer": a time metric or "none"
};

// Whether an item's rows match a selector (see above).
bool selector_matches(const std::string& selector, const Row& first_row_of_item);

// The mean of `column` over the items matching `selector`; `items` counts those that have it.
struct SelectionMean {
  double mean = 0.0;
  int items = 0;
  std::vector<int> indices;  // the items averaged
};
SelectionMean selection_mean(const std::string& selector, const Column& column,
                             const std::map<int, std::vector<const Row*>>& items);

// The first selection against the second on `runs` (runs[0]: the folder reported; at least
// one run); `seed` makes the probe points' bootstrap reproducible.
// `difference`: the effect is the difference of the means, not their ratio. `lossy_expected`:
// the claim is about the loss itself (a finding's "lossy": "expected", e.g. a layer limit
// exercised on purpose), so overflowed or dropped rows are named in the basis, not a defect.
// `tie_bands`, `practical_bands`: as evaluate_findings.
Comparison compare_selections(const std::string& first_selector, const Column& first_column,
                              const std::string& second_selector, const Column& second_column,
                              const std::vector<RunView>& runs, uint64_t seed,
                              bool difference = false, bool lossy_expected = false,
                              const TieBands& tie_bands = {},
                              const PracticalBands& practical_bands = {});

// The practical band of a column: its "metric:stat" entry, else its metric's, else 0.
double practical_band(const PracticalBands& bands, const Column& column);

// `findings` as validated by the suite loader; `tie_bands`: per metric the band of no effect
// that A/A controls measured (aa_controls.h), for ratios over runs (the wider of the two
// columns' bands, never below kSmallestRatio); `practical_bands`: per column or metric the
// suite's band of differences that do not matter (the wider of the two columns').
std::vector<FindingResult> evaluate_findings(const nlohmann::json& findings,
                                             const std::vector<RunView>& runs,
                                             const TieBands& tie_bands = {},
                                             const PracticalBands& practical_bands = {});

// "0.61x [0.58, 0.64]" or "+0.012 [+0.010, +0.015]".
std::string interval_text(const EffectInterval& interval);

}  // namespace dv
