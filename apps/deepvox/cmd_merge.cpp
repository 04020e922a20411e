// `deepvox merge`: joins the result folders of one sharded suite run into one folder and report
// (experiments/harness/merge.h).
#include <cstdio>

#include "apps/deepvox/commands.h"
#include "experiments/harness/merge.h"

namespace dv::cli {

Runner add_merge(CLI::App& app) {
  struct Options {
    std::vector<std::string> folders;
    std::string out;
    bool allow_missing = false;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand("merge", "join shard folders of a suite run into one report");
  cmd->add_option("folders", opt->folders, "the shards' result folders")->required();
  cmd->add_option("--out", opt->out, "results root (default: the one the shards are in)");
  cmd->add_flag("--allow-missing", opt->allow_missing,
                "merge what finished; the report names missing shards (SLURM merge job)");
  return [opt] {
    const std::string folder = merge_shards(opt->folders, opt->out, opt->allow_missing);
    std::printf("deepvox merge: report: %s/report.md\n", folder.c_str());
    return 0;
  };
}

}  // namespace dv::cli
