// stderr logging with a warning counter (see log.h).
#include "core/log.h"

#include <atomic>
#include <cstdio>
#include <mutex>

namespace dv {
namespace {
std::atomic<int> g_warnings{0};
std::atomic<bool> g_quiet{false};
std::mutex g_mutex;
}  // namespace

void log_warning(const std::string& message) {
  ++g_warnings;
  std::lock_guard lock(g_mutex);
  std::fprintf(stderr, "deepvox: warning: %s\n", message.c_str());
}

void log_info(const std::string& message) {
  if (g_quiet) return;
  std::lock_guard lock(g_mutex);
  std::fprintf(stderr, "deepvox: %s\n", message.c_str());
}

int warning_count() {
  return g_warnings;
}
void set_quiet(bool quiet) {
  g_quiet = quiet;
}

}  // namespace dv
