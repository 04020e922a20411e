// dsm_figures: the figures every storage strategy reports (see dsm_storage.h).
#include "dsm/storage/dsm_storage.h"

#include <algorithm>

#include "core/error.h"

namespace dv {

DsmHostNodes DsmStorage::host_nodes() const {
  throw Error("storage '" + name() + "' cannot copy its nodes out; generate with 'compact'");
}

nlohmann::json dsm_figures(const DsmStorage& storage, const std::vector<DsmTexelRecord>& records) {
  int64_t nodes = 0, needed = 0, max_layers = 0, non_empty = 0, overflowed = 0, recompressed = 0,
          walk_overflows = 0;
  double max_error = 0.0, max_overflow_error = 0.0;
  for (const DsmTexelRecord& r : records) {
    nodes += r.stored;
    needed += r.nodes;
    max_layers = std::max<int64_t>(max_layers, r.stored);
    non_empty += r.stored > 0;
    max_error = std::max<double>(max_error, r.error);
    if (r.flags & (kDsmStorageOverflow | kDsmRecompressed | kDsmNodesMerged)) {
      ++overflowed;
      max_overflow_error = std::max<double>(max_overflow_error, r.error);
    }
    recompressed += (r.flags & kDsmRecompressed) != 0;
    walk_overflows += (r.flags & kDsmWalkOverflow) != 0;
  }
  const double texels = double(std::max<size_t>(records.size(), 1));
  return {{"bytes_allocated", storage.bytes_allocated()},
          {"bytes_in_nodes", nodes * storage.bytes_per_node()},
          {"nodes", nodes},
          {"nodes_needed", needed},
          {"texels", int64_t(records.size())},
          {"mean_layers", double(nodes) / texels},
          {"mean_layers_nonempty", non_empty ? double(nodes) / double(non_empty) : 0.0},
          {"max_layers", max_layers},
          {"max_error", max_error},
          {"overflowed_texels", overflowed},
          {"overflow_max_error", max_overflow_error},
          {"recompressed_texels", recompressed},
          {"walk_overflow_texels", walk_overflows},
          {"strategy", storage.own_figures()}};
}

}  // namespace dv
