// Kernel side of the `beer` storage: the "Beer shadow map" of Unreal Engine 5's heterogeneous
// volumes: per texel two nodes, entry (depth where light
// starts to fall, transmittance just behind it) and exit (depth where it stops falling, final
// transmittance), 2 x 8 = 16 bytes per texel, constant-time lookups. Between them V' follows
// Beer-Lambert's law for the constant extinction that joins the two nodes,
// V'(z) = v_in (v_out / v_in)^((z - z_in) / (z_out - z_in)), so one homogeneous slab is
// reproduced exactly and everything else is an exponential fit through two points: steps at
// translucent surfaces inside the span are smeared into the exponential, and an opaque exit
// (v_out = 0) darkens the whole span (the ratio is floored at kBeerVisibilityFloor, the level at
// which the DSM walk stops, so the curve stays finite and reaches 0 only at z_out). Before the
// entry V' = 1, at it the value before its step (a surface entry stores the step's after-value as
// v_in); from z_out on V' = v_out. Generation streams the texel's exact visibility function (the
// eps = 0 compressor's nodes) through BeerSink, which keeps only the last lit node (refined by a
// step at its depth) and the first node that reaches the final value: compares only, so CPU and
// CUDA store the same nodes; the lookup's exp/log give values, not decisions. Host and device
// code.
#pragma once

#include <cmath>
#include <cstdint>

#include "core/hd.h"
#include "cuda/buffer.h"
#include "cuda/read_only.h"
#include "engine/dsm/node_search.h"

namespace dv {

inline constexpr float kBeerEmptyDepth = 3.402823466e38f;  // the largest float: never reached
inline constexpr double kBeerVisibilityFloor = 1e-6;       // = kDsmSaturatedVisibility

// A texel's two nodes, aligned to their size so that a lookup reads them with one vector load
// (cuda/read_only.h).
struct alignas(16) BeerTexel {
  DsmNode entry{kBeerEmptyDepth, 1.0f};
  DsmNode exit{kBeerEmptyDepth, 1.0f};
};

// Keeps the entry and exit nodes of a stream of nodes of a non-increasing V; never refuses.
struct BeerSink {
  BeerTexel texel;
  bool falling = false;  // a node below 1 has been seen
  DV_HD bool emit(float z, float v) {
    if (!falling) {
      if (v >= 1.0f) {
        texel.entry = {z, 1.0f};
        return true;
      }
      falling = true;
      const bool step_at_entry = texel.entry.z == kBeerEmptyDepth || texel.entry.z == z;
      if (step_at_entry) texel.entry = {z, v};
      texel.exit = {z, v};
      return true;
    }
    if (v < texel.exit.v) texel.exit = {z, v};
    return true;
  }
  DV_HD int stored() const { return falling ? 2 : 0; }
  // A bound on max |V' - V|: between the two nodes both curves lie in [v_out, v_in].
  DV_HD float error_bound() const { return falling ? texel.entry.v - texel.exit.v : 0.0f; }
};

struct BeerReader {
  View<const BeerTexel> texels;

  DV_HD float visibility(int64_t texel, float z, int&) const {
    const BeerTexel t = read_only(texels.data + texel);
    if (!(z > t.entry.z)) return 1.0f;
    if (!(z < t.exit.z)) return t.exit.v;
    if (!(double(t.entry.v) > kBeerVisibilityFloor)) return t.exit.v;
    const double fraction = (double(z) - t.entry.z) / (double(t.exit.z) - t.entry.z);
    const double ratio =
        (double(t.exit.v) > kBeerVisibilityFloor ? double(t.exit.v) : kBeerVisibilityFloor) /
        t.entry.v;
    return float(t.entry.v * exp(fraction * log(ratio)));
  }
};

}  // namespace dv
