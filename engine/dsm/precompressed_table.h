// Hadwiger et al. 2006 §3.2: pre-compressed visibility of one volume step. With the density
// taken as linear between the samples d0 (step start) and d1 (step end), the visibility along
// the step is V(a + u (b - a)) = V(a) exp(-(b - a) tau(u)), tau(u) = u * the mean extinction of
// the transfer function over the densities d0 .. d0 + (d1 - d0) u. The table holds, for every
// pair of density nodes (`bins` nodes spanning the transfer function's density range, its ends
// included), where the DSM compressor puts at most kTableNodes interior nodes of that function:
// sharp transfer-function edges (isosurfaces) are captured at moderate sampling rates.
// A lookup takes the nearest nodes of d0 and d1 and moves each table node to the position along
// the step where the density equals the table's density there (nodes sit at features of the
// transfer function, which are densities); the values at the nodes and the step's end are exact
// for the linear density (transfer_sigma_mean, engine/scene/volume_sampling.h), so quantising the
// densities to nodes moves nodes but never biases the visibility. (Earlier tables stored tau at
// bin centres: densities outside the transfer function's range were read at the first or last
// bin's centre, inside its edge, and the whole medium absorbed too much; science review
// 2026-12-04.) Host and device code (lookup); building is on the host
// (engine/dsm/precompressed_table.cpp).
#pragma once

#include <cstdint>
#include <vector>

#include "core/hd.h"
#include "cuda/buffer.h"
#include "engine/scene/scene_view.h"

namespace dv {

inline constexpr int kTableNodes = 4;

struct PrecompressedStep {
  float s[kTableNodes];  // interior node positions in (0, 1), increasing
  int32_t count;
};

struct PrecompressedTables {
  View<const PrecompressedStep> steps;  // per table: bins * bins, [node(d0) * bins + node(d1)]
  View<const int32_t> object_table;     // per object: first step of its table, or -1
  View<const dvec2> domain;             // per object: density range the nodes span
  int bins = 0;                         // nodes per density axis, >= 2

  DV_HD bool has(int32_t object) const {
    return object_table.size > 0 && object_table[object] >= 0;
  }
  // The node nearest to `density` (clamped to the domain).
  DV_HD int node(int32_t object, double density) const {
    const dvec2 d = domain[object];
    const double x = (density - d.x) / (d.y - d.x) * double(bins - 1);
    return int(min_value(max_value(x + 0.5, 0.0), double(bins - 1)));
  }
  DV_HD double node_density(int32_t object, int i) const {
    const dvec2 d = domain[object];
    return d.x + (d.y - d.x) * double(i) / double(bins - 1);
  }
  DV_HD const PrecompressedStep& step(int32_t object, int i, int j) const {
    return steps[object_table[object] + int64_t(i) * bins + j];
  }
};

// Tables for every volume object of `scene` (its objects and transfer functions, copied to the
// host): `bins` nodes per density axis, each step compressed so that |V' - V| <= table_eps for a
// step of the object's own length (starting at V = 1). Objects without a volume get -1.
struct PrecompressedTableData {
  std::vector<PrecompressedStep> steps;
  std::vector<int32_t> object_table;
  std::vector<dvec2> domain;
};
PrecompressedTableData build_precompressed_tables(const SceneData& scene, int bins,
                                                  float table_eps);

}  // namespace dv
