// The shadow-method options `render` and `probe` share: --shadows NAME, --param key=value, and
// the deep-shadow-map shortcuts --storage, --dsm-res, --eps, --filter (the dsm method's
// storage, res, eps and filter parameters; any other method rejects them as unknown) and
// --voxelizer (the transmittance-slicemap method's voxelizer parameter).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "strategies/shadow/shadow_method.h"

namespace dv::cli {

struct ShadowOptions {
  std::string name = "reference";
  std::vector<std::string> params;
  std::string storage, filter, voxelizer;
  // Given or not; the values are checked once, by the method that reads them.
  std::optional<int> dsm_res;
  std::optional<double> eps;
};

void add_shadow_options(CLI::App* cmd, ShadowOptions& options);
std::unique_ptr<ShadowMethod> make_shadow_method(const ShadowOptions& options);

}  // namespace dv::cli
