// Wall-clock marks of one process's phases (argument parsing, input loading, device ready, work,
// output), in milliseconds since main() began. Commands put them in their stats JSON so that a
// slow process start is measured phase by phase, not only around the whole process (a start-up
// time has a goal). Marks may come from any thread.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace dv {

// The origin of every mark: main() calls it first. Without it the first mark is the origin.
void start_wall_phases();
// Records the time since the origin under `name` (a later mark of the same name is kept too).
void mark_wall_phase(const std::string& name);
// [{"phase": name, "ms": time since the origin}, ...] in the order of the marks.
nlohmann::json wall_phases_json();

}  // namespace dv
