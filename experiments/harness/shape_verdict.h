// Verdicts of shape rows: a paper's ratio (two of its cells, one over the other) or difference
// (a cell minus the no-shadow frame) beside our 95 % interval of the same quantity over runs
// (findings.h's compare_selections), and the sentence that sums a table's rows up. A row
// reproduces the paper when the paper's value lies inside our interval, or within the stated
// relative band of it (the interval widened by the band at each end: ratios low / (1 + band) to
// high * (1 + band), differences each end moved out by band * |end|); else it differs. It is not
// comparable where the paper prints no number on a side, divides 0 by 0 (or anything by 0), or
// where we have no interval (nothing measured, one run, lost data) or 0 against 0 (our ratio
// fell back to a difference because a side is 0). docs/suite-format.md, "paper"'s shape.
#pragma once

#include <string>
#include <vector>

#include "experiments/harness/findings.h"

namespace dv {

constexpr double kDefaultShapeBand = 0.10;

struct ShapeVerdict {
  enum class Kind { inside, within_band, differs, not_comparable };
  Kind kind = Kind::not_comparable;
  std::string text;  // "reproduces (inside our interval)", "differs (ours 0.45x the paper's)", ...
  bool reproduces() const { return kind == Kind::inside || kind == Kind::within_band; }
};

// The paper's `paper_first` over (or, `difference`, minus) `paper_second` (NaN: the paper prints
// no number) against `ours`, the comparison of the same two selections; `band`: relative.
ShapeVerdict shape_verdict(double paper_first, double paper_second, const Comparison& ours,
                           bool difference, double band);

// One printed shape row: its name, verdict and our two sides' means; `time`: the sides are times
// in ms (their means are the row's load).
struct ShapeRow {
  std::string what;
  ShapeVerdict verdict;
  double first = 0.0, second = 0.0;
  bool time = false;
};

// "4 of 9 rows reproduce the paper (2 inside our 95 % interval, 2 within ±10 %): A; B; ...;
// 3 differ: C (ours 0.45x the paper's); ...; 2 not comparable (E; F). Our loads: 1.2–4.1 ms
// where the rows reproduce, 0.52–0.98 ms where they differ."
std::string shape_sentence(const std::vector<ShapeRow>& rows, double band);

}  // namespace dv
