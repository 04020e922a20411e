// Kernel side of the `fourier` storage (Fourier opacity maps, Jansen & Bavoil 2010): the
// optical-depth density sigma(u) over the texel's normalised depth u in [0, 1] is projected on
// K frequencies, a_k = 2 int sigma cos(2 pi k u) du, b_k = 2 int sigma sin(2 pi k u) du, and a
// lookup reconstructs the integral in closed form,
//   tau(u) = total u + sum_k (a_k sin(2 pi k u) + b_k (1 - cos(2 pi k u))) / (2 pi k),
// with total = a_0 / 2 = tau(1) (the optical depth in the series: the texel's total less its
// last step, optical_depth_basis.h). The texel's nodes span u in [kFourierMargin,
// 1 - kFourierMargin], so that a surface at the first node does not wrap round to the end of
// the periodic series. Truncation rings (Gibbs): tau overshoots a step by up to ~9% of it on
// both sides, may dip below 0 before the first surface and exceed the total before the last,
// and smears a step over ~1/K of the range; tau is clamped at 0 (transmittance in [0, 1]).
// Per texel kTexelHeaderFloats + 1 + 2K floats, texel t's at t * stride: z_first, z_last, the
// texel's total optical depth, the series' total, a_1, b_1, .., a_K, b_K. Pieces of mass are
// projected exactly (uniform density over a segment: the mean of cos/sin over it is cos/sin at its
// middle times sinc of its half-width). Harmonics by the angle-addition recurrence from one sin/cos
// pair. Host and device code.
#pragma once

#include <cstdint>

#include "core/hd.h"
#include "cuda/buffer.h"
#include "strategies/storage/optical_depth_basis.h"

namespace dv {

inline constexpr int kMaxFourierFrequencies = 32;
inline constexpr double kFourierMargin = 0.1;
inline constexpr double kTwoPi = 6.283185307179586477;

DV_HD inline int fourier_stride(int frequencies) {
  return kTexelHeaderFloats + 1 + 2 * frequencies;
}

// u of depth z in a texel whose nodes span [first, last].
DV_HD inline double fourier_depth_u(float first, float last, float z) {
  const double span = double(last) - double(first);
  const double s = span > 0.0 ? (double(z) - double(first)) / span : 0.0;
  return kFourierMargin + (1.0 - 2.0 * kFourierMargin) * s;
}

// cos(k x) and sin(k x) for k = 1, 2, .. by angle addition from (cos x, sin x).
struct Harmonics {
  double c1, s1, c, s;
  DV_HD explicit Harmonics(double x) : c1(cos(x)), s1(sin(x)), c(1.0), s(0.0) {}
  DV_HD void next() {
    const double cn = c * c1 - s * s1;
    s = s * c1 + c * s1;
    c = cn;
  }
};

struct FourierSink {
  float* texel;  // the texel's record; z_first and z_last are already written (range pass)
  int frequencies;
  double sums[1 + 2 * kMaxFourierFrequencies] = {};  // total, a_1, b_1, ..
  OpticalDepthPieces pieces;

  DV_HD bool emit(float z, float v) {
    pieces.last_z = texel[1];
    pieces.push(z, v, *this);
    return true;
  }
  DV_HD void add(float z0, float z1, double mass) {
    const double u0 = fourier_depth_u(texel[0], texel[1], z0);
    const double u1 = fourier_depth_u(texel[0], texel[1], z1);
    const double half_width = 0.5 * kTwoPi * (u1 - u0);  // pi w: sinc(pi k w) for k = 1, 2, ..
    Harmonics middle(kTwoPi * 0.5 * (u0 + u1)), width(half_width);
    sums[0] += mass;
    for (int k = 1; k <= frequencies; ++k) {
      middle.next(), width.next();
      const double x = half_width * k;
      const double sinc = x > 0.0 ? width.s / x : 1.0;
      sums[2 * k - 1] += 2.0 * mass * (middle.c * sinc);
      sums[2 * k] += 2.0 * mass * (middle.s * sinc);
    }
  }
  DV_HD void write() const {
    texel[2] = float(pieces.tau);
    for (int k = 0; k <= 2 * frequencies; ++k) texel[kTexelHeaderFloats + k] = float(sums[k]);
  }
};

// tau(u) of a texel's coefficients (total, a_1, b_1, ..), unclamped.
DV_HD inline double fourier_optical_depth(const float* coefficients, int frequencies, double u) {
  double tau = double(coefficients[0]) * u;
  Harmonics h(kTwoPi * u);
  for (int k = 1; k <= frequencies; ++k) {
    h.next();
    tau += (double(coefficients[2 * k - 1]) * h.s + double(coefficients[2 * k]) * (1.0 - h.c)) /
           (kTwoPi * k);
  }
  return tau;
}

struct FourierReader {
  View<const float> data;  // texels * fourier_stride(frequencies)
  int frequencies = 8;

  DV_HD float visibility(int64_t t, float z, int&) const {
    const float* texel = data.data + t * fourier_stride(frequencies);
    const float* coefficients = texel + kTexelHeaderFloats;
    float outside;
    if (visibility_outside_range(texel, z, outside)) return outside;
    const double u = fourier_depth_u(texel[0], texel[1], z);
    return float(exp(-max_value(fourier_optical_depth(coefficients, frequencies, u), 0.0)));
  }
};

}  // namespace dv
