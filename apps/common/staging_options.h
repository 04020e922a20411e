// The staging options `render` and `view` share: --ground (a ground plane under any scene) and
// --no-ground (none, not even under a staged scene), parsed into the loader's StagingOptions
// (engine/scene/default_staging.h; without either, staged scenes get a ground).
#pragma once

#include <CLI/CLI.hpp>

#include "engine/scene/default_staging.h"

namespace dv::cli {

// `options` must outlive the parse (the flags' callbacks write to it).
void add_staging_options(CLI::App* cmd, StagingOptions& options);

// The flag that gives `options` back on a command line ("" for the default).
const char* staging_flag(const StagingOptions& options);

}  // namespace dv::cli
