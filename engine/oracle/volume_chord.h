// The oracle's optical depth through a density volume, in closed form on host and device.
//
// Inside one grid cell the trilinear density along a ray is a cubic in the ray parameter, and
// the transfer function maps density to extinction piecewise linearly (constant beyond its end
// points). So the ray is cut at cell faces; in each cell the cubic is cut where it turns
// (roots of its derivative) and, on each monotone stretch, where it crosses a transfer control
// point (a bracketed root, found to 1e-14 of the cell); on every piece the extinction is
// alpha + beta * cubic, which Simpson's rule integrates exactly (a cell whose corners span no
// control point is one such piece: its cubic's mean suffices). Bricks whose extinction is
// zero everywhere (SceneView::brick_empty, flagged from the range of their samples) are crossed
// in one step. No tolerance and no adaptivity: the answer is exact up to rounding, and the cost
// per cell is fixed (4 cubic coefficients, at most 2 turning points, one root per control point
// crossed).
#pragma once

#include <cmath>

#include "core/hd.h"
#include "core/math.h"
#include "engine/scene/scene_view.h"
#include "engine/scene/volume_sampling.h"

namespace dv {

// d(u) = c[0] + c[1] u + c[2] u^2 + c[3] u^3 over u in [0, 1].
struct Cubic {
  double c[4];
  DV_HD double operator()(double u) const { return c[0] + u * (c[1] + u * (c[2] + u * c[3])); }
};

// The trilinear density of a cell along a straight stretch on which the cell fractions run
// linearly from f0 (u = 0) to f1 (u = 1): the nested lerps of trilinear() with polynomials.
DV_HD inline Cubic cell_density_cubic(const double corner[8], const double f0[3],
                                      const double f1[3]) {
  // lerp(a, b, f) with a, b polynomials of degree < 3 and f = f0 + (f1 - f0) u: a + (b - a) f.
  auto lerp = [](const double* a, const double* b, double p, double q, double* out) {
    double diff[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    out[0] = a[0] + diff[0] * p;
    out[1] = a[1] + diff[1] * p + diff[0] * q;
    out[2] = a[2] + diff[2] * p + diff[1] * q;
    out[3] = diff[2] * q;
  };
  const double p[3] = {f0[0], f0[1], f0[2]};
  const double q[3] = {f1[0] - f0[0], f1[1] - f0[1], f1[2] - f0[2]};
  double x[4][4], y[2][4];
  for (int k = 0; k < 4; ++k) {  // along x: corners 2k and 2k + 1
    const double a[3] = {corner[2 * k], 0.0, 0.0}, b[3] = {corner[2 * k + 1], 0.0, 0.0};
    lerp(a, b, p[0], q[0], x[k]);
  }
  lerp(x[0], x[1], p[1], q[1], y[0]);  // along y at z = 0
  lerp(x[2], x[3], p[1], q[1], y[1]);  // along y at z = 1
  Cubic d;
  lerp(y[0], y[1], p[2], q[2], d.c);
  return d;
}

// The transfer function's extinction on one linear piece: sigma = alpha + beta * density, the
// piece chosen by a density strictly inside it (or beyond an end point).
DV_HD inline void transfer_piece(const TransferPoint* p, int n, double density, double& alpha,
                                 double& beta) {
  beta = 0.0;
  if (density <= p[0].density) {
    alpha = p[0].sigma;
    return;
  }
  if (density >= p[n - 1].density) {
    alpha = p[n - 1].sigma;
    return;
  }
  const int k = transfer_segment(p, n, density);
  const double span = p[k + 1].density - p[k].density;
  if (!(span > 0.0)) {
    alpha = p[k + 1].sigma;
    return;
  }
  beta = (p[k + 1].sigma - p[k].sigma) / span;
  alpha = p[k].sigma - beta * p[k].density;
}

// Where the cubic, monotone on [lo, hi], equals `level` (which lies between its end values):
// regula falsi guarded by bisection, to 1e-14 of the interval. (The extinction is continuous at
// a control point, so an error e in the cut costs only O(e^2) of the integral.)
DV_HD inline double monotone_cubic_root(const Cubic& d, double lo, double hi, double level) {
  double f_lo = d(lo) - level, f_hi = d(hi) - level;
  for (int i = 0; i < 80 && hi - lo > 1e-14; ++i) {
    double x = f_hi != f_lo ? lo + (hi - lo) * (f_lo / (f_lo - f_hi)) : 0.5 * (lo + hi);
    // Bisect every third step, or when regula falsi stalls at an end.
    if (i % 3 == 2 || !(x > lo && x < hi)) x = 0.5 * (lo + hi);
    const double fx = d(x) - level;
    if (fx == 0.0) return x;
    if ((fx < 0.0) == (f_lo < 0.0)) {
      lo = x;
      f_lo = fx;
    } else {
      hi = x;
      f_hi = fx;
    }
  }
  return 0.5 * (lo + hi);
}

// Integral over u in [0, 1] of the transfer function's extinction of d(u).
DV_HD inline double transfer_integral_of_cubic(const TransferPoint* p, int n, const Cubic& d) {
  // Turning points of d in (0, 1): roots of c1 + 2 c2 u + 3 c3 u^2, in order.
  double cuts[4] = {0.0, 1.0, 1.0, 1.0};
  int n_cuts = 1;
  const double A = 3.0 * d.c[3], B = 2.0 * d.c[2], C = d.c[1];
  double r[2];
  int n_roots = 0;
  const double scale = fabs(A) + fabs(B) + fabs(C);
  if (fabs(A) > 1e-12 * scale) {
    const double disc = B * B - 4.0 * A * C;
    if (disc > 0.0) {
      const double qq = -0.5 * (B + (B >= 0.0 ? sqrt(disc) : -sqrt(disc)));
      r[0] = qq / A;
      r[1] = qq != 0.0 ? C / qq : r[0];
      n_roots = 2;
    }
  } else if (fabs(B) > 0.0) {
    r[0] = -C / B;
    n_roots = 1;
  }
  if (n_roots == 2 && r[1] < r[0]) {
    const double t = r[0];
    r[0] = r[1];
    r[1] = t;
  }
  for (int i = 0; i < n_roots; ++i)
    if (r[i] > cuts[n_cuts - 1] && r[i] < 1.0) cuts[n_cuts++] = r[i];
  cuts[n_cuts++] = 1.0;

  auto piece = [&](double a, double b) {
    if (!(b > a)) return 0.0;
    const double da = d(a), dm = d(0.5 * (a + b)), db = d(b);
    double alpha, beta;
    transfer_piece(p, n, dm, alpha, beta);
    return (b - a) * (alpha + beta * (da + 4.0 * dm + db) / 6.0);
  };
  double total = 0.0;
  for (int m = 0; m + 1 < n_cuts; ++m) {
    const double lo = cuts[m], hi = cuts[m + 1];
    const double d_hi = d(hi);
    double from = lo, d_from = d(lo);
    const bool rising = d_hi >= d_from;
    // Control points strictly between the density where the last cut left it and the stretch's
    // end, in the order the ray meets them: each bracket holds a sign change (a repeated control
    // point, a step of the transfer function, is cut once).
    for (int j = 0; j < n; ++j) {
      const int k = rising ? j : n - 1 - j;
      const double level = p[k].density;
      const bool inside =
          rising ? (level > d_from && level < d_hi) : (level < d_from && level > d_hi);
      if (!inside) continue;
      const double at = monotone_cubic_root(d, from, hi, level);
      total += piece(from, at);
      from = at;
      d_from = d(at);
    }
    total += piece(from, hi);
  }
  return total;
}

// The integral over u in [0, 1] of the extinction along a stretch of one cell (the fractions
// running from f0 to f1). Trilinear interpolation stays within the corners' range, so when no
// control point lies strictly inside that range the extinction is one linear piece along the
// whole stretch: alpha + beta * (the cubic's mean), no turning points or roots to find.
DV_HD inline double cell_transfer_integral(const TransferPoint* p, int n, const double corner[8],
                                           const double f0[3], const double f1[3]) {
  double lo = corner[0], hi = corner[0];
  for (int k = 1; k < 8; ++k) {
    lo = min_value(lo, corner[k]);
    hi = max_value(hi, corner[k]);
  }
  const Cubic d = cell_density_cubic(corner, f0, f1);
  for (int k = 0; k < n; ++k)
    if (p[k].density > lo && p[k].density < hi) return transfer_integral_of_cubic(p, n, d);
  double alpha, beta;
  transfer_piece(p, n, 0.5 * (lo + hi), alpha, beta);
  if (beta == 0.0) return alpha;
  return alpha + beta * (d.c[0] + d.c[1] / 2.0 + d.c[2] / 3.0 + d.c[3] / 4.0);
}

// Optical depth of volume object o over the ray interval [t0, t1] (origin + t dir, world units).
DV_HD inline double volume_optical_depth(const SceneView& s, const ObjectView& o,
                                         const dvec3& origin, const dvec3& dir, double t0,
                                         double t1) {
  if (!(t1 > t0)) return 0.0;
  const VolumeView& v = s.volumes[o.volume];
  const TransferPoint* tf = s.transfer.data + o.transfer_first;
  const int n_tf = o.transfer_count;
  const dvec3 g0 = world_to_grid(o, origin + dir * t0);
  const dvec3 g1 = world_to_grid(o, origin + dir * t1);
  const dvec3 gd = (g1 - g0) / (t1 - t0);  // grid units per unit t
  auto grid_at = [&](double t) { return g0 + gd * (t - t0); };
  double total = 0.0;
  double t = t0;
  while (t < t1) {
    // The next integer plane inside [0, dims - 1] the ray crosses after t, on any axis, so that
    // [t, t_next] lies in one cell (the closed form below holds for one cell only).
    double t_next = t1;
    const dvec3 g = grid_at(t);
    for (int a = 0; a < 3; ++a) {
      if (gd[a] == 0.0) continue;
      const double hi = double(v.dims[a] - 1);
      double plane;
      if (gd[a] > 0.0) {
        plane = g[a] < 0.0 ? 0.0 : double(int(g[a])) + 1.0;
        if (plane > hi) continue;
      } else {
        if (g[a] <= 0.0) continue;
        plane = g[a] > hi ? hi : double(int(g[a]));
        if (plane >= g[a]) plane -= 1.0;
        if (plane < 0.0) continue;
      }
      double tp = t0 + (plane - g0[a]) / gd[a];
      if (!(tp > t)) {  // t lies on that plane already (rounding): the next one is ahead
        plane += gd[a] > 0.0 ? 1.0 : -1.0;
        if (plane > hi || plane < 0.0) continue;
        tp = t0 + (plane - g0[a]) / gd[a];
      }
      if (tp > t && tp < t_next) t_next = tp;
    }
    const dvec3 g_mid = grid_at(0.5 * (t + t_next));
    ivec3 brick;
    if (in_empty_brick(s, o, g_mid, brick)) {
      // Zero extinction to the brick's far side: cross it in one step.
      const double exit = t + brick_exit_distance(o, brick, g, gd);
      t = min_value(t1, max_value(t_next, exit));
      continue;
    }
    // The cell around the stretch's midpoint, and the fractions at its two ends.
    int cell[3];
    cell_of_grid_point(v, g_mid, cell);
    const dvec3 g_end = grid_at(t_next);
    double f0[3], f1[3];
    for (int a = 0; a < 3; ++a) {
      const double hi = double(v.dims[a] - 1);
      const bool flat = v.dims[a] < 2;
      f0[a] = flat ? 0.0 : clamp_value(g[a], 0.0, hi) - double(cell[a]);
      f1[a] = flat ? 0.0 : clamp_value(g_end[a], 0.0, hi) - double(cell[a]);
    }
    double corner[8];
    cell_corners(s, v, cell, corner);
    total += (t_next - t) * cell_transfer_integral(tf, n_tf, corner, f0, f1);
    t = t_next;
  }
  return total;
}

}  // namespace dv
