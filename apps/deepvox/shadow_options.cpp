// add_shadow_options / make_shadow_method (see shadow_options.h).
#include "apps/deepvox/shadow_options.h"

namespace dv::cli {

void add_shadow_options(CLI::App* cmd, ShadowOptions& o) {
  cmd->add_option("--shadows", o.name, "shadow method (see `deepvox list`)")->capture_default_str();
  cmd->add_option("--param", o.params, "shadow-method parameter key=value (repeatable)");
  cmd->add_option("--storage", o.storage,
                  "dsm: storage strategy (compact, texture3d, chunked, blocked, moments, fourier)");
  cmd->add_option("--dsm-res", o.dsm_res, "dsm: texels per side of each map")
      ->check(CLI::Range(1, 65536));
  cmd->add_option("--eps", o.eps, "dsm: error bound of the compressed visibility functions")
      ->check(CLI::Range(0.0, 4.0));
  cmd->add_option("--filter", o.filter, "dsm: none or bilinear")
      ->check(CLI::IsMember({"none", "bilinear"}));
  cmd->add_option("--voxelizer", o.voxelizer,
                  "transmittance-slicemap: voxelizer filling its grids (see `deepvox list`)");
}

std::unique_ptr<ShadowMethod> make_shadow_method(const ShadowOptions& o) {
  std::vector<std::string> params = o.params;
  if (!o.storage.empty()) params.push_back("storage=" + o.storage);
  if (o.dsm_res > 0) params.push_back("res=" + std::to_string(o.dsm_res));
  if (o.eps >= 0.0) {
    char eps[64];
    std::snprintf(eps, sizeof eps, "eps=%.9g", o.eps);
    params.push_back(eps);
  }
  if (!o.filter.empty()) params.push_back("filter=" + o.filter);
  if (!o.voxelizer.empty()) params.push_back("voxelizer=" + o.voxelizer);
  return shadow_registry().create(o.name, StrategyParams::parse(params));
}

}  // namespace dv::cli
