// Host side of the deep-shadow-map storage family (texture3d, chunked, blocked, compact arrive
// with the DSM work). A storage strategy is a sink the generation walk writes nodes into and
// then answers lookups; here is the part every strategy shares: its name, its parameters and
// its memory figures.
#pragma once

#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "strategies/registry.h"

namespace dv {

struct StorageFigures {
  int64_t bytes_allocated = 0;
  int64_t bytes_in_nodes = 0;
  int64_t nodes = 0;
  int64_t overflowed_texels = 0;
};

class DsmStorage {
 public:
  virtual ~DsmStorage() = default;
  virtual std::string name() const = 0;
  virtual nlohmann::json params() const = 0;
  virtual StorageFigures figures() const = 0;
};

Registry<DsmStorage>& storage_registry();

}  // namespace dv
