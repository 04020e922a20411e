// Progress of a suite run on a terminal: what runs, done / left, elapsed time and an estimate
// from the mean time per finished experiment, rewritten in place on stderr. Quiet when stderr
// is not a terminal (logs, CI), unless forced.
#pragma once

#include <chrono>
#include <string>

namespace dv {

class Progress {
 public:
  Progress(int total, bool enabled);
  static bool stderr_is_terminal();
  void start(int done, const std::string& what);  // before an experiment
  void finish();                                  // clears the line
  double elapsed_seconds() const;

 private:
  int total_;
  bool enabled_;
  std::chrono::steady_clock::time_point begin_;
};

}  // namespace dv
