// Command-line mistakes as one clear line and exit code 2 (the README's "bad input"): the bad
// word named, and the nearest known subcommand or option suggested by edit distance
// ("unknown subcommand 'renderr'; did you mean 'render'?"). --help and --version keep CLI11's
// own output and exit 0.
#pragma once

#include <CLI/CLI.hpp>

namespace dv::cli {

// Parses argv into `app` (every subcommand already added). Returns -1 when the command line is
// good and the chosen subcommand should run, else the exit code (0 after help, 2 after an error
// message on stderr).
int parse_command_line(CLI::App& app, int argc, char** argv);

}  // namespace dv::cli
