// What the storages that fold a texel into a fixed record (`moments`, `fourier`, `occupancy`)
// share: each folds one texel's
// compressed visibility function V' (the generation walk's nodes, engine/dsm/dsm_generator.h) into
// a few numbers per texel instead of storing its nodes. V' is turned into optical depth tau = -ln
// V' (capped at kMaxOpticalDepth, Muenstermann et al. 2018's ABSORBANCE_MAX_VALUE, so that opaque
// surfaces stay finite), whose increments are fed to the basis as pieces: a step at a twin depth (a
// surface) as a point mass, a segment between two node depths (a medium) as a uniform density over
// it. Depth is normalised per texel between its first and last node, found by a first walk (`range`
// pass). The texel's last step (a surface at z_last: an opaque receiver or caster, or the last
// translucent sheet) is kept out of the basis and applied exactly, as both papers leave opaque
// geometry to a depth-tested pass: a basis would smear its large mass backwards (a floor under
// translucent casters would shadow itself). Each record starts with [z_first, z_last, total optical
// depth]; lookups answer exactly outside the range (1 up to and at z_first, exp(-total) after
// z_last) as the node storages do, and from the basis inside it. Host and device code.
#pragma once

#include <cstdint>

#include "core/hd.h"
#include "core/math.h"

namespace dv {

// tau of a fully opaque texel: transmittance exp(-10) = 4.5e-5 behind an opaque surface.
inline constexpr double kMaxOpticalDepth = 10.0;

// Per texel, first in its record: z_first, z_last (range pass), total optical depth (write pass).
inline constexpr int kTexelHeaderFloats = 3;

DV_HD inline double capped_optical_depth(float v) {
  return v > 0.0f ? min_value(-log(double(v)), kMaxOpticalDepth) : kMaxOpticalDepth;
}

// Range pass: the depths of the first and last node of a texel (count 0: no node).
struct DepthRangeSink {
  float first = 0.0f, last = 0.0f;
  int count = 0;
  DV_HD bool emit(float z, float) {
    if (count++ == 0) first = z;
    last = z;
    return true;
  }
};

// Turns the node stream (z, v) into optical-depth pieces for a basis with
// `add(float z_begin, float z_end, double mass)` (z_begin == z_end: a point mass); point masses
// at `last_z` (the texel's last step) are held back. `tau` ends as the total optical depth.
struct OpticalDepthPieces {
  float last_z = 0.0f;
  float previous_z = 0.0f;
  double tau = 0.0;
  bool started = false;

  template <class Basis>
  DV_HD void push(float z, float v, Basis& basis) {
    const double next = max_value(capped_optical_depth(v), tau);  // V' is non-increasing
    const double mass = next - tau;
    const float begin = started ? previous_z : z;
    if (mass > 0.0 && !(begin == z && z == last_z)) basis.add(begin, z, mass);
    started = true;
    previous_z = z, tau = next;
  }
};

// A lookup outside its texel's range: 1 up to and at z_first (the value before its step),
// exp(-total) after z_last; false inside, where the record's reconstruction answers.
DV_HD inline bool visibility_outside_range(const float* texel, float z, float& visibility) {
  if (!(z > texel[0])) {
    visibility = 1.0f;
    return true;
  }
  if (z > texel[1]) {
    visibility = float(exp(-double(texel[2])));
    return true;
  }
  return false;
}

}  // namespace dv
