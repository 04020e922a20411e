// Terminal progress line (progress.h).
#include "experiments/harness/progress.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

namespace dv {

Progress::Progress(int total, bool enabled, std::string status_file)
    : total_(total),
      enabled_(enabled),
      status_file_(std::move(status_file)),
      begin_(std::chrono::steady_clock::now()) {
  write_status(0, "starting");
}

void Progress::write_status(int done, const std::string& what) const {
  if (status_file_.empty()) return;
  const std::string temp = status_file_ + ".tmp";  // renamed over: a reader never sees half
  std::ofstream(temp) << done << " " << total_ << " " << what << "\n";
  std::error_code ec;
  std::filesystem::rename(temp, status_file_, ec);
}

bool Progress::stderr_is_terminal() {
  return isatty(STDERR_FILENO) == 1;
}

double Progress::elapsed_seconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - begin_).count();
}

void Progress::start(int done, const std::string& what) {
  write_status(done, what);
  if (!enabled_) return;
  const double elapsed = elapsed_seconds();
  char eta[32] = "?";
  if (done > 0) std::snprintf(eta, sizeof eta, "%.0fs", elapsed / done * (total_ - done));
  // One line that fits a terminal: \r rewrites it only while it does not wrap.
  const std::string shown = what.size() > 72 ? what.substr(0, 69) + "..." : what;
  std::fprintf(stderr, "\r\033[K[%d/%d] %d done, %d left, %.0fs elapsed, ~%s to go: %s", done + 1,
               total_, done, total_ - done, elapsed, eta, shown.c_str());
  std::fflush(stderr);
}

void Progress::finish() {
  if (!enabled_) return;
  std::fprintf(stderr, "\r\033[K");
  std::fflush(stderr);
}

}  // namespace dv
