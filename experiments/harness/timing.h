// Repeated timings: samples per named pass over the timed repetitions (the warm-up is not
// added), reported as median, min and max in milliseconds. Pass times come from PassTimer or the
// strategies' own per-pass figures, so CUDA passes are synchronised where they are measured.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace dv {

class RowSink;

struct Spread {
  double median = 0.0, min = 0.0, max = 0.0;
};
// The median of an even count is the mean of the two middle samples; `samples` non-empty.
Spread spread_of(std::vector<double> samples);

class PassTimes {
 public:
  void add(const std::string& pass, double milliseconds);
  // Rows "<prefix><pass>_ms" with stats median, min, max (unit ms) and one "repetitions" row;
  // every repetition goes to the sink's samples (driver.h) under the same metric.
  void emit(RowSink& rows, const std::string& prefix) const;
  bool empty() const { return passes_.empty(); }

 private:
  std::vector<std::pair<std::string, std::vector<double>>> passes_;  // first-seen order
};

}  // namespace dv
