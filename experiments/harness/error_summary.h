// The summary of absolute errors every accuracy measurement reports: count, max, mean and the
// 50th, 90th, 95th and 99th percentiles (nearest rank: the smallest error with at least that
// fraction of the errors at or below it). Max and p99 saturate at 1 for map methods on many
// scenes (a few texels always miss an edge), so the lower quantiles are the columns that rank.
// Used by the suite's shadow driver.
#pragma once

#include <cstddef>
#include <vector>

namespace dv {

struct ErrorSummary {
  size_t count = 0;
  double max = 0.0, mean = 0.0;                       // 0 when there are no errors
  double p50 = 0.0, p90 = 0.0, p95 = 0.0, p99 = 0.0;  // likewise
};

ErrorSummary summarize_errors(std::vector<double> errors);

// The nearest-rank `fraction` quantile of ascending `sorted` (not empty): its element at rank
// ceil(fraction * n), clamped to 1..n.
double nearest_rank(const std::vector<double>& sorted, double fraction);

}  // namespace dv
