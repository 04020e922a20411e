// Shelf packing of the triangles' atlas cells (see atlas_packing.h), on the host.
#include "strategies/voxelizer/atlas_packing.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/error.h"
#include "strategies/voxelizer/atlas_device.h"
#include "strategies/voxelizer/work_items.h"

namespace dv {

namespace {

// Cell side for a triangle of `leg` (sqrt of twice its area) at `texel_size`, capped at `side`.
int32_t cell_size(double leg, double texel_size, int side) {
  const double s = std::ceil(leg / texel_size);
  return int32_t(std::clamp(s, 1.0, double(side)));
}

// Places the cells in `order` by shelves; false when they do not fit.
bool shelf_pack(std::vector<AtlasCell>& cells, const std::vector<int64_t>& order, int side) {
  int64_t x = 0, y = 0, row = 0;
  for (int64_t t : order) {
    AtlasCell& c = cells[size_t(t)];
    if (x + c.size > side) {
      y += row;
      x = 0;
      row = 0;
    }
    if (row == 0) row = c.size;
    if (y + c.size > side) return false;
    c.x = int32_t(x);
    c.y = int32_t(y);
    x += c.size;
  }
  return true;
}

}  // namespace

AtlasLayout pack_atlas(const TriangleSoup& soup, const GridSpec& spec, int side) {
  if (side < 1 || side > kMaxAtlasSide)
    throw InputError("atlas", "side " + std::to_string(side) + " must be in [1, " +
                                  std::to_string(kMaxAtlasSide) + "]");
  const int64_t triangles = soup.triangle_count();
  if (triangles > int64_t(side) * side)
    throw InputError("atlas", std::to_string(triangles) + " triangles do not fit a " +
                                  std::to_string(side) + "^2 atlas (one texel each at least)");
  const GridTransform to_grid = grid_transform(spec);
  std::vector<double> legs(static_cast<size_t>(triangles));
  std::vector<AtlasCell> cells(static_cast<size_t>(triangles));
  double total_area2 = 0.0;
  for (int64_t t = 0; t < triangles; ++t) {
    dvec3 g[3];
    for (int k = 0; k < 3; ++k) g[k] = to_grid.apply(soup.corners[size_t(3 * t + k)]);
    const double area2 = std::sqrt(squared_length(triangle_normal(g[0], g[1], g[2])));
    legs[size_t(t)] = std::isfinite(area2) ? std::sqrt(area2) : 0.0;
    total_area2 += legs[size_t(t)] * legs[size_t(t)];
    int longest = 0;
    double best = -1.0;
    for (int k = 0; k < 3; ++k) {
      const double len2 = squared_length(g[(k + 1) % 3] - g[k]);
      if (len2 > best) {
        best = len2;
        longest = k;
      }
    }
    cells[size_t(t)].corner = (longest + 2) % 3;  // the corner not on the longest edge
  }

  AtlasLayout layout;
  layout.side = side;
  double texel_size = std::max(std::sqrt(total_area2) / double(side), 1e-300);
  // Cell sizes grow with the leg, so one order by decreasing leg serves every density.
  std::vector<int64_t> order(static_cast<size_t>(triangles));
  std::iota(order.begin(), order.end(), int64_t(0));
  std::stable_sort(order.begin(), order.end(),
                   [&](int64_t a, int64_t b) { return legs[size_t(a)] > legs[size_t(b)]; });
  for (;; texel_size *= 1.05) {
    for (int64_t t = 0; t < triangles; ++t)
      cells[size_t(t)].size = cell_size(legs[size_t(t)], texel_size, side);
    if (shelf_pack(cells, order, side)) break;
  }
  layout.texel_size = texel_size;
  std::vector<int64_t> counts(static_cast<size_t>(triangles));
  for (int64_t t = 0; t < triangles; ++t)
    counts[size_t(t)] = atlas_cell_texels(cells[size_t(t)].size);
  layout.cells = std::move(cells);
  layout.texel_first = work_item_offsets(counts);
  return layout;
}

}  // namespace dv
