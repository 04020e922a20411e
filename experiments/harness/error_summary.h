// The summary of absolute errors every accuracy measurement reports: count, max, mean and the
// 99th percentile (nearest rank: the smallest error with at least 99 % of the errors at or
// below it). Used by the suite's shadow driver.
#pragma once

#include <cstddef>
#include <vector>

namespace dv {

struct ErrorSummary {
  size_t count = 0;
  double max = 0.0, mean = 0.0, p99 = 0.0;  // 0 when there are no errors
};

ErrorSummary summarize_errors(std::vector<double> errors);

}  // namespace dv
