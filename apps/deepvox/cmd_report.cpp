// `deepvox report DIR`: (re)builds a result folder's Markdown report and plots from its rows,
// metadata and images (experiments/harness/report.h), e.g. on the host after a GPU run.
#include <cstdio>

#include "apps/deepvox/commands.h"
#include "experiments/harness/report.h"

namespace dv::cli {

Runner add_report(CLI::App& app) {
  auto folder = std::make_shared<std::string>();
  CLI::App* cmd =
      app.add_subcommand("report", "rebuild the report and plots of a suite result folder");
  cmd->add_option("folder", *folder, "result folder (holds meta.json and rows.csv)")->required();
  return [folder] {
    build_report(*folder);
    std::printf("deepvox report: %s/report.md\n", folder->c_str());
    return 0;
  };
}

}  // namespace dv::cli
