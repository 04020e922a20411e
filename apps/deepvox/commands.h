// Subcommands of the `deepvox` CLI. Each adds its options to the CLI11 app and returns the
// function that runs it (exit code).
#pragma once

#include <functional>

#include <CLI/CLI.hpp>

namespace dv::cli {

using Runner = std::function<int()>;

Runner add_probe(CLI::App& app);
Runner add_render(CLI::App& app);
Runner add_info(CLI::App& app);
Runner add_list(CLI::App& app);
Runner add_voxelize(CLI::App& app);
Runner add_dsm(CLI::App& app);
Runner add_suite(CLI::App& app);
Runner add_merge(CLI::App& app);
Runner add_report(CLI::App& app);
Runner add_advise(CLI::App& app);
Runner add_view(CLI::App& app);  // only where the viewer is built (DEEPVOX_WITH_VIEWER)
Runner add_help(CLI::App& app);  // after the others: it prints theirs

}  // namespace dv::cli
