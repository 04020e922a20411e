// Error summaries (error_summary.h).
#include "experiments/harness/error_summary.h"

#include <algorithm>
#include <cmath>

namespace dv {

double nearest_rank(const std::vector<double>& sorted, double fraction) {
  const size_t rank = size_t(std::ceil(fraction * double(sorted.size())));
  return sorted[std::clamp<size_t>(rank, 1, sorted.size()) - 1];
}

double quantile_bound(const std::vector<double>& sorted, double fraction, double z) {
  const double n = double(sorted.size());
  const double rank = fraction * n + z * std::sqrt(fraction * (1.0 - fraction) * n);
  const double rounded = z >= 0.0 ? std::ceil(rank) : std::floor(rank);
  return sorted[size_t(std::clamp(rounded, 1.0, n)) - 1];
}

ErrorSummary summarize_errors(std::vector<double> errors) {
  ErrorSummary s;
  s.count = errors.size();
  if (errors.empty()) return s;
  std::sort(errors.begin(), errors.end());
  for (double e : errors) s.mean += e / double(errors.size());
  s.max = errors.back();
  s.p50 = nearest_rank(errors, 0.50);
  s.p90 = nearest_rank(errors, 0.90);
  s.p95 = nearest_rank(errors, 0.95);
  s.p99 = nearest_rank(errors, 0.99);
  s.p95_lo = quantile_bound(errors, 0.95, -1.96);
  s.p95_hi = quantile_bound(errors, 0.95, 1.96);
  s.mean_lo = s.mean_hi = s.mean;
  if (errors.size() >= 2) {
    double squares = 0.0;
    for (double e : errors) squares += (e - s.mean) * (e - s.mean);
    const double n = double(errors.size());
    const double half = 1.96 * std::sqrt(squares / (n - 1.0) / n);
    s.mean_lo = std::max(0.0, s.mean - half);  // |errors| are never negative
    s.mean_hi = s.mean + half;
  }
  return s;
}

}  // namespace dv
