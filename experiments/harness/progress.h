// Progress of a suite run on a terminal: what runs, done / left, elapsed time and an estimate
// from the mean time per finished experiment, rewritten in place on stderr. Quiet when stderr
// is not a terminal (logs, CI), unless forced. A status file, when named, gets the same state as
// one line "DONE TOTAL WHAT" (rewritten whole), for a parent that shows its workers (workers.h).
#pragma once

#include <chrono>
#include <string>

namespace dv {

class Progress {
 public:
  Progress(int total, bool enabled, std::string status_file = "");
  static bool stderr_is_terminal();
  void start(int done, const std::string& what);  // before an experiment
  void finish();                                  // clears the line
  // Writes "DONE TOTAL WHAT" to the status file (no-op without one).
  void write_status(int done, const std::string& what) const;
  double elapsed_seconds() const;

 private:
  int total_;
  bool enabled_;
  std::string status_file_;
  std::chrono::steady_clock::time_point begin_;
};

}  // namespace dv
