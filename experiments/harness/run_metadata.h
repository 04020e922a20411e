// Metadata every result file carries so a run can be reproduced: version, git commit (at build
// time, with the dirty flag, and at run time where git answers), build type, compiler, CPU
// model and threads, host name, CUDA_VISIBLE_DEVICES, CUDA runtime and driver versions, GPU name
// and clocks, backend and the command line. The CLI and the experiment harness share it.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "cuda/execute.h"

namespace dv {

void remember_command_line(int argc, char** argv);
// The command line given to remember_command_line, arguments joined by spaces.
const std::string& command_line();
nlohmann::json run_metadata(Backend backend);

// The commit the binary was built from: 12 hex digits, "-dirty" appended when tracked files
// differed, or "unknown".
std::string build_git_sha();
// gethostname(), or "unknown".
std::string host_name();
// The first line of /proc/cpuinfo's "model name", or "unknown".
std::string cpu_model();

}  // namespace dv
