// dsm_figures: the figures every storage strategy reports (see dsm_storage.h), from the sums
// over the records (strategies/storage/dsm_records.h).
#include "strategies/storage/dsm_storage.h"

#include <algorithm>

#include "core/error.h"

namespace dv {

DsmHostNodes DsmStorage::host_nodes() const {
  throw Error("storage '" + name() + "' cannot copy its nodes out; generate with 'compact'");
}

nlohmann::json dsm_figures(const DsmStorage& storage, const DsmRecordSums& s) {
  const double texels = double(std::max<int64_t>(s.texels, 1));
  return {{"bytes_allocated", storage.bytes_allocated()},
          {"bytes_in_nodes", s.nodes * storage.bytes_per_node()},
          {"nodes", s.nodes},
          {"nodes_needed", s.needed},
          {"texels", s.texels},
          {"mean_layers", double(s.nodes) / texels},
          {"mean_layers_nonempty", s.non_empty ? double(s.nodes) / double(s.non_empty) : 0.0},
          {"max_layers", s.max_layers},
          {"max_error", double(s.max_error)},
          {"overflowed_texels", s.overflowed},
          {"overflow_max_error", double(s.overflow_max_error)},
          {"recompressed_texels", s.recompressed},
          {"walk_overflow_texels", s.walk_overflows},
          {"strategy", storage.own_figures()}};
}

}  // namespace dv
