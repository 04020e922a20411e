// The shadow-method options `render` and `probe` share: --shadows NAME, --param key=value, and
// the deep-shadow-map shortcuts --storage, --dsm-res, --eps, --filter (the dsm method's
// storage, res, eps and filter parameters; any other method rejects them as unknown) and
// --voxelizer (the transmittance-slicemap method's voxelizer parameter). The default method is
// `auto` (the effect planner); --explain prints its decisions.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "strategies/shadow/shadow_method.h"

namespace dv::cli {

struct ShadowOptions {
  std::string name = "auto";
  std::vector<std::string> params;
  std::string storage, filter, voxelizer;
  int dsm_res = 0;
  double eps = -1.0;
  bool explain = false;  // --explain: print the planner's decisions
};

void add_shadow_options(CLI::App* cmd, ShadowOptions& options);
std::unique_ptr<ShadowMethod> make_shadow_method(const ShadowOptions& options);
// With --explain, prints the method's last plan in plain words to stdout (headed `label`); a
// method that does not plan says so.
void explain_shadows(const ShadowOptions& options, const ShadowMethod& method,
                     const std::string& label);

}  // namespace dv::cli
