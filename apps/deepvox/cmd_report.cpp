// `deepvox report`: (re)builds a result folder's Markdown report and plots from its rows, samples,
// metadata and images (experiments/harness/report.h), e.g. on the host after a GPU run; further
// result folders of the same suite file are recorded in DIR/runs.json as independent runs that the
// findings' intervals pool.
#include <cstdio>

#include "apps/deepvox/commands.h"
#include "experiments/harness/recorded_runs.h"
#include "experiments/harness/report.h"

namespace dv::cli {

Runner add_report(CLI::App& app) {
  auto folder = std::make_shared<std::string>();
  auto runs = std::make_shared<std::vector<std::string>>();
  CLI::App* cmd =
      app.add_subcommand("report", "rebuild the report and plots of a suite result folder");
  cmd->add_option("folder", *folder, "result folder (holds meta.json and rows.csv)")->required();
  cmd->add_option("runs", *runs,
                  "further runs of the same suite file (result folders) for the findings' "
                  "intervals; recorded in FOLDER/runs.json");
  return [folder, runs] {
    if (!runs->empty()) record_runs(*folder, *runs);
    build_report(*folder);
    std::printf("deepvox report: %s/report.md\n", folder->c_str());
    return 0;
  };
}

}  // namespace dv::cli
