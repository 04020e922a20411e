// Error summaries (error_summary.h).
#include "experiments/harness/error_summary.h"

#include <algorithm>
#include <cmath>

namespace dv {

ErrorSummary summarize_errors(std::vector<double> errors) {
  ErrorSummary s;
  s.count = errors.size();
  if (errors.empty()) return s;
  std::sort(errors.begin(), errors.end());
  for (double e : errors) s.mean += e / double(errors.size());
  s.max = errors.back();
  const size_t rank = size_t(std::ceil(0.99 * double(errors.size())));
  s.p99 = errors[std::clamp<size_t>(rank, 1, errors.size()) - 1];
  return s;
}

}  // namespace dv
