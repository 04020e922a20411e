// Hadwiger et al. 2006 §3.2: pre-compressed visibility of one volume step. With the density
// taken as linear between the samples d0 (step start) and d1 (step end), the optical depth per
// unit length along the step, tau(s) = integral_0^s sigma(TF(d0 + (d1 - d0) u)) du for s in
// [0, 1], is tabulated for every pair of density bins and compressed, with the DSM compressor,
// into at most kTableNodes interior nodes (s_i, tau(s_i)). A step [a, b] then contributes
// V(a + s_i (b - a)) = V(a) exp(-(b - a) tau(s_i)) at the nodes and V(a) exp(-(b - a) tau(1)) at
// its end: sharp transfer-function edges (isosurfaces) are captured at moderate sampling rates.
// Host and device code (lookup); building is on the host (engine/dsm/precompressed_table.cpp).
#pragma once

#include <cstdint>
#include <vector>

#include "core/hd.h"
#include "cuda/buffer.h"
#include "engine/scene/scene_view.h"

namespace dv {

inline constexpr int kTableNodes = 4;

struct PrecompressedStep {
  float s[kTableNodes];    // interior node positions in (0, 1), increasing
  float tau[kTableNodes];  // optical depth per unit length up to s
  float tau_end;           // ... up to 1
  int32_t count;
};

struct PrecompressedTables {
  View<const PrecompressedStep> steps;  // per table: bins * bins, [bin(d0) * bins + bin(d1)]
  View<const int32_t> object_table;     // per object: first step of its table, or -1
  View<const dvec2> domain;             // per object: density range the bins cover
  int bins = 0;

  DV_HD bool has(int32_t object) const {
    return object_table.size > 0 && object_table[object] >= 0;
  }
  DV_HD int bin(int32_t object, double density) const {
    const dvec2 d = domain[object];
    const double x = d.y > d.x ? (density - d.x) / (d.y - d.x) : 0.0;
    return int(min_value(max_value(x * bins, 0.0), double(bins - 1)));
  }
  DV_HD const PrecompressedStep& step(int32_t object, double d0, double d1) const {
    return steps[object_table[object] + int64_t(bin(object, d0)) * bins + bin(object, d1)];
  }
};

// Tables for every volume object of `scene` (its objects and transfer functions, copied to the
// host):
// `bins` per density axis, each step compressed so that |V' - V| <= table_eps for a step of the
// object's own length (starting at V = 1). Objects without a volume get -1.
struct PrecompressedTableData {
  std::vector<PrecompressedStep> steps;
  std::vector<int32_t> object_table;
  std::vector<dvec2> domain;
};
PrecompressedTableData build_precompressed_tables(const SceneData& scene, int bins,
                                                  float table_eps);

}  // namespace dv
