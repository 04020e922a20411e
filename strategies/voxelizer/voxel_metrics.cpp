// Word-wise comparison of a grid with the exact reference (see voxel_metrics.h).
#include "strategies/voxelizer/voxel_metrics.h"

#include <bit>

namespace dv {

nlohmann::json VoxelMetrics::to_json() const {
  return {{"filled", filled},
          {"reference_filled", reference_filled},
          {"missing", missing},
          {"extra", extra},
          {"borderline", borderline},
          {"missing_outside_band", missing_outside_band},
          {"extra_outside_band", extra_outside_band}};
}

VoxelMetrics compare_with_exact(const VoxelGrid& method, const ExactVoxelization& reference) {
  const GridSpec& a = method.spec();
  const GridSpec& b = reference.exact.spec();
  if (a.res != b.res) throw Error("compare_with_exact: grids of different resolutions");
  if (reference.grown.spec().res != b.res || reference.shrunk.spec().res != b.res)
    throw Error("compare_with_exact: the reference was computed without its borderline band");
  const std::vector<uint32_t> m = method.words(), e = reference.exact.words(),
                              g = reference.grown.words(), s = reference.shrunk.words();
  VoxelMetrics out;
  for (size_t i = 0; i < m.size(); ++i) {
    out.filled += std::popcount(m[i]);
    out.reference_filled += std::popcount(e[i]);
    out.missing += std::popcount(e[i] & ~m[i]);
    out.extra += std::popcount(m[i] & ~e[i]);
    out.borderline += std::popcount(g[i] & ~s[i]);
    out.missing_outside_band += std::popcount(s[i] & ~m[i]);
    out.extra_outside_band += std::popcount(m[i] & ~g[i]);
  }
  return out;
}

}  // namespace dv
