// Kernel side of the `moments` storage (strategies/storage/power_moments.h for the method): per
// texel kTexelHeaderFloats + 1 + n floats, texel t's at t * stride: z_first, z_last, the total
// optical depth, b_0 (the optical depth in the moments: the total less the last step), b_1..b_n
// (normalised power moments of depth mapped to [-1, 1] over the texel's range). The sink folds
// the texel's nodes into the moments in double precision and writes floats when the texel ends.
// Host and device code.
#pragma once

#include <cstdint>

#include "core/hd.h"
#include "cuda/buffer.h"
#include "strategies/storage/optical_depth_basis.h"
#include "strategies/storage/power_moments.h"

namespace dv {

DV_HD inline int moments_stride(int moments) {
  return kTexelHeaderFloats + 1 + moments;
}

struct PowerMomentSink {
  float* texel;  // the texel's record; z_first and z_last are already written (range pass)
  int moments;
  double sums[kMaxPowerMoments + 1] = {};
  OpticalDepthPieces pieces;

  DV_HD double depth_u(float z) const {
    const double span = double(texel[1]) - double(texel[0]);
    return span > 0.0 ? -1.0 + 2.0 * ((double(z) - double(texel[0])) / span) : -1.0;
  }
  DV_HD bool emit(float z, float v) {
    pieces.last_z = texel[1];
    pieces.push(z, v, *this);
    return true;
  }
  DV_HD void add(float z0, float z1, double mass) {
    add_power_moments(sums, moments, depth_u(z0), depth_u(z1), mass);
  }
  DV_HD void write() const {
    texel[2] = float(pieces.tau);
    texel[kTexelHeaderFloats] = float(sums[0]);
    for (int k = 1; k <= moments; ++k)
      texel[kTexelHeaderFloats + k] = sums[0] > 0.0 ? float(sums[k] / sums[0]) : 0.0f;
  }
};

struct MomentsReader {
  View<const float> data;  // texels * moments_stride(moments)
  int moments = 4;
  float bias = 0.0f;
  float overestimation = 0.0f;

  DV_HD float visibility(int64_t t, float z, int&) const {
    return moments == 6 ? visibility_of<6>(t, z) : visibility_of<4>(t, z);
  }

  template <int n>
  DV_HD float visibility_of(int64_t t, float z) const {
    const float* texel = data.data + t * moments_stride(n);
    float outside;
    if (visibility_outside_range(texel, z, outside)) return outside;
    const double mass = texel[kTexelHeaderFloats];
    if (!(mass > 0.0)) return 1.0f;
    double b[n + 1];
    for (int k = 1; k <= n; ++k) b[k] = texel[kTexelHeaderFloats + k];
    const double span = double(texel[1]) - double(texel[0]);
    const double u = -1.0 + 2.0 * ((double(z) - double(texel[0])) / span);
    return float(exp(-mass * moment_fraction_in_front<n>(b, u, bias, overestimation)));
  }
};

}  // namespace dv
