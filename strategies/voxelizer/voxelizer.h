// Host side of the voxelizer family (slicemap, atlas, sat, atlas-compute, exact arrive with the
// voxelization work): a named strategy with its parameters that fills a binary grid.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "strategies/registry.h"

namespace dv {

class Voxelizer {
 public:
  virtual ~Voxelizer() = default;
  virtual std::string name() const = 0;
  virtual nlohmann::json params() const = 0;
};

Registry<Voxelizer>& voxelizer_registry();

}  // namespace dv
