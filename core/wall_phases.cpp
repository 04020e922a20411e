// Wall-clock phase marks of one process (see wall_phases.h).
#include "core/wall_phases.h"

#include <chrono>
#include <mutex>
#include <optional>
#include <utility>
#include <vector>

namespace dv {

namespace {

using Clock = std::chrono::steady_clock;

struct WallPhases {
  std::mutex mutex;
  std::optional<Clock::time_point> origin;
  std::vector<std::pair<std::string, double>> marks;
};

WallPhases& wall_phases() {
  static WallPhases phases;
  return phases;
}

}  // namespace

void start_wall_phases() {
  WallPhases& w = wall_phases();
  std::lock_guard lock(w.mutex);
  w.origin = Clock::now();
  w.marks.clear();
}

void mark_wall_phase(const std::string& name) {
  const Clock::time_point now = Clock::now();
  WallPhases& w = wall_phases();
  std::lock_guard lock(w.mutex);
  if (!w.origin) w.origin = now;
  w.marks.emplace_back(name, std::chrono::duration<double, std::milli>(now - *w.origin).count());
}

nlohmann::json wall_phases_json() {
  WallPhases& w = wall_phases();
  std::lock_guard lock(w.mutex);
  nlohmann::json out = nlohmann::json::array();
  for (const auto& [name, ms] : w.marks) out.push_back({{"phase", name}, {"ms", ms}});
  return out;
}

}  // namespace dv
