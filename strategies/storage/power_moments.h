// Power moments of optical depth and the transmittance bound they give (Peters & Klein 2015,
// "Moment Shadow Mapping", Hamburger 4MSM; Muenstermann, Krumpen, Klein & Peters 2018,
// "Moment-Based Order-Independent Transparency", §3-4 and its 4/6 power-moment resolve).
// Depth u in [-1, 1]; b_0 the total optical depth, b_k (k = 1..n, n = 4 or 6) the moments of
// the optical-depth distribution divided by b_0. Reconstruction at depth u: the moments are
// biased towards a fixed interior vector, b <- (1 - alpha) b + alpha b_bias (alpha 5e-7 for 4,
// 5e-6 for 6 moments: the paper's values for 32-bit floats; b_bias (0, .375, 0, .375) and
// (0, .48, 0, .451, 0, .45)), the Hankel matrix (b_{i+j}) is factored (LDL^T, Cholesky without
// roots), the kernel polynomial B^-1 (1, u, .., u^m) gives m support points besides u, and the
// fraction of b_0 in front of u is the interpolating polynomial through the weights (1 for
// support points in front of u, 0 behind, `overestimation` (paper: 0.25) at u itself) applied
// to the moments: between the Chebyshev-Markov-Krein lower (0) and upper (1) bounds.
// Safeguards beyond the bias: pivots of the factorisation at least kMomentPivotFloor, support
// points kept within kMomentRootBound and apart from u by kMomentRootSeparation, the fraction
// clamped to [0, 1] (a NaN, which only input far outside the moment space could still give,
// becomes `overestimation`). Roots come from the quadratic formula (degree 2) or bisection between
// the derivative's roots (degree 3): only + - * / and sqrt, so CPU and CUDA take the same decisions
// from the same stored moments. The resolve is a template on the moment count, so that its arrays
// are registers on the GPU: with the count a run-time value they lived on the stack (304 bytes of
// local memory for every lookup, ptxas -v on sm_90). Host and device code; double precision.
#pragma once

#include "core/hd.h"
#include "core/math.h"

namespace dv {

inline constexpr int kMaxPowerMoments = 6;
inline constexpr double kMomentPivotFloor = 1e-14;
inline constexpr double kMomentRootBound = 1e6;
inline constexpr double kMomentRootSeparation = 1e-12;

DV_HD inline double default_moment_bias(int moments) {
  return moments == 6 ? 5e-6 : 5e-7;
}

// Moment k (1..6) of the bias vector of the paper's n-moment resolve.
DV_HD inline double moment_bias_vector(int moments, int k) {
  if (k % 2 == 1) return 0.0;
  if (moments == 4) return 0.375;
  return k == 2 ? 0.48 : (k == 4 ? 0.451 : 0.45);
}

// Adds, for k = 0..n, mass times the mean of u^k over [u0, u1] (uniform density; u0 == u1: a
// point mass): (u0^k + u0^(k-1) u1 + .. + u1^k) / (k + 1).
DV_HD inline void add_power_moments(double* sums, int moments, double u0, double u1, double mass) {
  double p0[kMaxPowerMoments + 1], p1[kMaxPowerMoments + 1];
  p0[0] = p1[0] = 1.0;
  for (int k = 1; k <= moments; ++k) p0[k] = p0[k - 1] * u0, p1[k] = p1[k - 1] * u1;
  for (int k = 0; k <= moments; ++k) {
    double mean = 0.0;
    for (int j = 0; j <= k; ++j) mean += p0[j] * p1[k - j];
    sums[k] += mass * (mean / double(k + 1));
  }
}

// p(x) = c[0] + c[1] x + .. + c[degree] x^degree.
DV_HD inline double evaluate_polynomial(const double* c, int degree, double x) {
  double p = c[degree];
  for (int i = degree - 1; i >= 0; --i) p = p * x + c[i];
  return p;
}

// A root of p in [lo, hi] by bisection when p changes sign there, else the end nearer zero.
DV_HD inline double bisect_root(const double* c, int degree, double lo, double hi) {
  double plo = evaluate_polynomial(c, degree, lo);
  const double phi = evaluate_polynomial(c, degree, hi);
  if ((plo < 0.0) == (phi < 0.0) || plo == 0.0 || phi == 0.0)
    return (plo < 0.0 ? -plo : plo) <= (phi < 0.0 ? -phi : phi) ? lo : hi;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid == lo || mid == hi) break;
    const double pm = evaluate_polynomial(c, degree, mid);
    if ((pm < 0.0) == (plo < 0.0))
      lo = mid, plo = pm;
    else
      hi = mid;
  }
  return 0.5 * (lo + hi);
}

// The real roots of c[0] + c[1] x + c[2] x^2 (c[2] != 0), ascending; a complex pair (only from
// rounding) gives its real part twice.
DV_HD inline void quadratic_roots(const double* c, double* roots) {
  const double disc = max_value(c[1] * c[1] - 4.0 * c[2] * c[0], 0.0);
  const double q = -0.5 * (c[1] + (c[1] < 0.0 ? -sqrt(disc) : sqrt(disc)));
  double a = q != 0.0 ? q / c[2] : -0.5 * c[1] / c[2];
  double b = q != 0.0 ? c[0] / q : a;
  roots[0] = min_value(a, b), roots[1] = max_value(a, b);
}

// The m (2 or 3) support points besides u: roots of the kernel polynomial c of degree m,
// bounded by kMomentRootBound (a vanishing leading coefficient puts a root at infinity).
template <int m>
DV_HD void kernel_roots(const double* c, double* roots) {
  double scale = 0.0;
  for (int i = 0; i <= m; ++i) scale = max_value(scale, c[i] < 0.0 ? -c[i] : c[i]);
  const double lead = c[m] < 0.0 ? -c[m] : c[m];
  const double bound = kMomentRootBound;
  if (lead <= scale / bound) {  // degree drops: one root far out, the rest from degree m - 1
    if constexpr (m == 2) {
      roots[0] = c[1] != 0.0 ? clamp_value(-c[0] / c[1], -bound, bound) : bound;
      roots[1] = bound;
    } else {
      quadratic_roots(c, roots);
      roots[2] = bound;
    }
  } else if constexpr (m == 2) {
    quadratic_roots(c, roots);
  } else {
    const double d[3] = {c[1], 2.0 * c[2], 3.0 * c[3]};  // derivative
    double turn[2];
    quadratic_roots(d, turn);
    roots[0] = bisect_root(c, 3, -bound, clamp_value(turn[0], -bound, bound));
    roots[1] =
        bisect_root(c, 3, clamp_value(turn[0], -bound, bound), clamp_value(turn[1], -bound, bound));
    roots[2] = bisect_root(c, 3, clamp_value(turn[1], -bound, bound), bound);
  }
  for (int i = 0; i < m; ++i) roots[i] = clamp_value(roots[i], -bound, bound);
}

// The fraction of b_0 in front of u from normalised moments moments[1..n] (moments[0] unused).
template <int n>
DV_HD double moment_fraction_in_front(const double* moments, double u, double bias,
                                      double overestimation) {
  static_assert(n == 4 || n == 6, "4 or 6 power moments");
  constexpr int m = n / 2;
  double b[kMaxPowerMoments + 1];
  b[0] = 1.0;
  for (int k = 1; k <= n; ++k) b[k] = (1.0 - bias) * moments[k] + bias * moment_bias_vector(n, k);
  // Hankel matrix H_ij = b[i + j] = L D L^T.
  double L[4][4] = {}, D[4];
  for (int i = 0; i <= m; ++i) {
    for (int j = 0; j < i; ++j) {
      double s = b[i + j];
      for (int k = 0; k < j; ++k) s -= L[i][k] * L[j][k] * D[k];
      L[i][j] = s / D[j];
    }
    double d = b[2 * i];
    for (int k = 0; k < i; ++k) d -= L[i][k] * L[i][k] * D[k];
    D[i] = max_value(d, kMomentPivotFloor);
  }
  // Kernel polynomial c = H^-1 (1, u, .., u^m).
  double c[4];
  c[0] = 1.0;
  for (int i = 1; i <= m; ++i) c[i] = c[i - 1] * u;
  for (int i = 0; i <= m; ++i)
    for (int k = 0; k < i; ++k) c[i] -= L[i][k] * c[k];
  for (int i = 0; i <= m; ++i) c[i] /= D[i];
  for (int i = m; i >= 0; --i)
    for (int k = i + 1; k <= m; ++k) c[i] -= L[k][i] * c[k];
  // Support points x[0] = u, x[1..m]; weights f; Newton divided differences.
  double x[4], f[4];
  x[0] = u, f[0] = overestimation;
  kernel_roots<m>(c, x + 1);
  for (int i = 1; i <= m; ++i) {
    for (int j = 0; j < i; ++j) {
      const double gap = x[i] - x[j];
      if ((gap < 0.0 ? -gap : gap) < kMomentRootSeparation)
        x[i] = x[j] + (gap < 0.0 ? -kMomentRootSeparation : kMomentRootSeparation);
    }
    f[i] = x[i] < u ? 1.0 : 0.0;
  }
  for (int j = 1; j <= m; ++j)
    for (int i = m; i >= j; --i) f[i] = (f[i] - f[i - 1]) / (x[i] - x[i - j]);
  // Monomial coefficients of the Newton form, then applied to the moments.
  double p[4] = {f[m], 0.0, 0.0, 0.0};
  for (int i = m - 1; i >= 0; --i) {
    for (int k = m - i; k >= 1; --k) p[k] = p[k - 1] - x[i] * p[k];
    p[0] = f[i] - x[i] * p[0];
  }
  double fraction = 0.0;
  for (int k = 0; k <= m; ++k) fraction += p[k] * b[k];
  return fraction == fraction ? clamp_value(fraction, 0.0, 1.0) : overestimation;
}

// The same for a moment count n (4 or 6) known at run time.
DV_HD inline double moment_fraction_in_front(const double* moments, int n, double u, double bias,
                                             double overestimation) {
  return n == 6 ? moment_fraction_in_front<6>(moments, u, bias, overestimation)
                : moment_fraction_in_front<4>(moments, u, bias, overestimation);
}

}  // namespace dv
