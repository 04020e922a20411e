// Warnings and progress messages on stderr. Warnings are counted so commands can report them
// (a glTF with unsupported optional extensions, skipped POINTS primitives, ...).
#pragma once

#include <string>

namespace dv {

void log_warning(const std::string& message);
void log_info(const std::string& message);
int warning_count();
void set_quiet(bool quiet);  // suppresses info messages (warnings still print)

}  // namespace dv
