// The summary of absolute errors every accuracy measurement reports: count, max, mean and the
// 50th, 90th, 95th and 99th percentiles (nearest rank: the smallest error with at least that
// fraction of the errors at or below it), with 95 % intervals over the points for the mean and
// the p95. Max and p99 saturate at 1 for map methods on many scenes (a few texels always miss an
// edge), so the lower quantiles are the columns that rank. Used by the suite's shadow driver.
#pragma once

#include <cstddef>
#include <vector>

namespace dv {

struct ErrorSummary {
  size_t count = 0;
  double max = 0.0, mean = 0.0;                       // 0 when there are no errors
  double p50 = 0.0, p90 = 0.0, p95 = 0.0, p99 = 0.0;  // likewise
  // 95 % intervals over the points (the points are the sample; a run's render is deterministic,
  // so repeated runs would not widen them): the mean's from the normal approximation, mean +-
  // 1.96 s / sqrt(n) (the mean itself for n < 2); the p95's from the binomial order statistic,
  // quantile_bound with z = -+1.96 (distribution-free).
  double mean_lo = 0.0, mean_hi = 0.0;
  double p95_lo = 0.0, p95_hi = 0.0;
};

ErrorSummary summarize_errors(std::vector<double> errors);

// The nearest-rank `fraction` quantile of ascending `sorted` (not empty): its element at rank
// ceil(fraction * n), clamped to 1..n.
double nearest_rank(const std::vector<double>& sorted, double fraction);

// A confidence bound of the `fraction` quantile of ascending `sorted` (not empty) from the
// normal approximation of the binomial order statistic: the element at rank
// fraction n + z sqrt(fraction (1 - fraction) n), rounded up for z >= 0 and down for z < 0,
// clamped to 1..n (z = 1.645: a one-sided 95 % upper bound; z = -+1.96: a two-sided 95 %
// interval).
double quantile_bound(const std::vector<double>& sorted, double fraction, double z);

}  // namespace dv
