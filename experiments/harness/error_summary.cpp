// Error summaries (error_summary.h).
#include "experiments/harness/error_summary.h"

#include <algorithm>
#include <cmath>

namespace dv {

double nearest_rank(const std::vector<double>& sorted, double fraction) {
  const size_t rank = size_t(std::ceil(fraction * double(sorted.size())));
  return sorted[std::clamp<size_t>(rank, 1, sorted.size()) - 1];
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
  return s;
}

}  // namespace dv
