// add_staging_options / staging_flag (see staging_options.h).
#include "apps/common/staging_options.h"

namespace dv::cli {

void add_staging_options(CLI::App* cmd, StagingOptions& options) {
  CLI::Option* ground = cmd->add_flag_callback(
      "--ground", [&options] { options.ground = GroundPlane::on; },
      "add an opaque ground plane just below the scene bounds (if none is named ground); "
      "default: only for scenes without lights, whose lights deepvox stages");
  cmd->add_flag_callback(
         "--no-ground", [&options] { options.ground = GroundPlane::off; },
         "no ground plane, not even under a scene whose lights deepvox stages")
      ->excludes(ground);
}

const char* staging_flag(const StagingOptions& options) {
  return options.ground == GroundPlane::on    ? " --ground"
         : options.ground == GroundPlane::off ? " --no-ground"
                                              : "";
}

}  // namespace dv::cli
