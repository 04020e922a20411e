// Metadata every result file carries so a run can be reproduced: version, git commit, build
// type, compiler, CUDA, device, backend and the command line.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "core/execute.h"

namespace dv::cli {

void remember_command_line(int argc, char** argv);
nlohmann::json run_metadata(Backend backend);

}  // namespace dv::cli
