// Adaptive Simpson quadrature with an explicit stack, a per-interval tolerance and a convergence
// flag: an integrator independent of the oracle's closed form (engine/oracle/volume_chord.h), to
// check it against. (It was the oracle's own integrator until the closed form replaced it.)
#pragma once

#include "core/hd.h"

namespace dv::test {

inline constexpr int kQuadratureMaxDepth = 40;

struct QuadratureResult {
  double value;
  bool converged;
};

template <class F>
DV_HD QuadratureResult adaptive_simpson(F&& f, double a, double b, double tolerance) {
  struct Interval {
    double a, b, fa, fm, fb, whole, tol;
    int depth;
  };
  Interval stack[kQuadratureMaxDepth + 2];
  int top = 0;
  const double fa = f(a), fb = f(b), m = 0.5 * (a + b), fm = f(m);
  stack[top++] = {a, b, fa, fm, fb, (b - a) / 6.0 * (fa + 4.0 * fm + fb), tolerance, 0};
  double sum = 0.0;
  bool converged = true;
  while (top > 0) {
    const Interval iv = stack[--top];
    const double mid = 0.5 * (iv.a + iv.b);
    const double lm = 0.5 * (iv.a + mid), rm = 0.5 * (mid + iv.b);
    const double flm = f(lm), frm = f(rm);
    const double left = (mid - iv.a) / 6.0 * (iv.fa + 4.0 * flm + iv.fm);
    const double right = (iv.b - mid) / 6.0 * (iv.fm + 4.0 * frm + iv.fb);
    const double delta = left + right - iv.whole;
    const bool ok = (delta < 0 ? -delta : delta) <= 15.0 * iv.tol;
    if (ok || iv.depth >= kQuadratureMaxDepth) {
      if (!ok) converged = false;
      sum += left + right + delta / 15.0;
      continue;
    }
    stack[top++] = {mid, iv.b, iv.fm, frm, iv.fb, right, 0.5 * iv.tol, iv.depth + 1};
    stack[top++] = {iv.a, mid, iv.fa, flm, iv.fm, left, 0.5 * iv.tol, iv.depth + 1};
  }
  return {sum, converged};
}

}  // namespace dv::test
