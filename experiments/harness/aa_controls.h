// A/A controls: an experiment with "aa_duplicates" runs every item twice (the copy's rows say
// "aa=copy" in `params`), so each pair measures the same work and any effect between them is
// noise, drift or the item's place in the run. Per pair and per timed metric (the samples'
// "timings") the effect copy / original gets the findings' interval over runs
// (effect_interval.h); from them:
// - the false-positive rate: the share of A/A intervals that exclude "no effect" (the fixed band
//   of kSmallestRatio); calibrated 95 % intervals make it about 5 % or less;
// - a tie band per metric: the 95th percentile (nearest rank) of |log(A/A effect)| over the
//   pairs, as a relative half-width (never below kSmallestRatio): an effect of a finding on that
//   metric smaller than identical configurations show is a tie (findings.h);
// - the false positives left once those bands apply.
// Pairs are matched by experiment, scene, strategy and params (less the "aa=copy" term) in the
// first run; only runs in which both were measured count (effect_interval.h).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "experiments/harness/effect_interval.h"
#include "experiments/harness/findings.h"

namespace dv {

struct AaPair {
  int original = 0, copy = 0;  // item indices
};

struct AaControls {
  std::vector<AaPair> pairs;
  size_t runs = 0;           // the most runs any A/A interval rests on
  int tested = 0;            // A/A intervals (pairs x timed metrics, at least 2 runs)
  int outside = 0;           // of them, excluding no effect (kSmallestRatio band)
  int outside_tie_band = 0;  // of them, excluding the metric's tie band
  TieBands tie_bands;        // per timed metric: relative half-width
  std::map<std::string, int> tested_by_metric;
};

// Whether a row's `params` mark an A/A copy (the term "aa=copy"): the Pareto fronts and plots
// leave copies out, since a copy repeats an item's work and is no configuration of its own.
bool is_aa_copy(const std::string& params);

// The A/A pairs among `runs[0]`'s items and what they measure (see above).
AaControls measure_aa_controls(const std::vector<RunView>& runs);

// "3 of 40 A/A intervals (7.5 %) exclude no effect (goal <= 5 %); with the tie bands from the
// A/A spread 0 of 40 (0 %)", or why there is none.
std::string aa_rate_text(const AaControls& aa);
// "generate_ms ±3.1 %, render_ms ±1 % (95th percentile of |A/A effect| over 4 pairs)".
std::string tie_bands_text(const AaControls& aa);

}  // namespace dv
