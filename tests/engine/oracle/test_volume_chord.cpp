// The closed-form optical depth through density volumes (engine/oracle/volume_chord.h): the
// cell's cubic against trilinear interpolation, the transfer integral of a cubic against
// adaptive Simpson refined to intervals of 2^-40 (kinks, steps, turning points, constant ends;
// cells whose corners span no control point, which take the cubic's mean),
// and the walk through a grid (cell faces met on the ray, empty bricks skipped) against the same
// walk with no brick flagged and against adaptive Simpson on the trilinear extinction.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "engine/oracle/volume_chord.h"
#include "tests/support/adaptive_simpson.h"
#include "tests/support/scene_builder.h"

namespace dv {
namespace {

TransferPoint tp(double density, double sigma) {
  return {density, dvec3(1.0), sigma};
}

// Its error is below 1e-11 on these functions: a kink or a step is refined down to an interval
// of 2^-40 (it may report that it did not converge there), and smooth pieces are cubics.
double simpson_reference(const std::vector<TransferPoint>& tf, const Cubic& d) {
  return test::adaptive_simpson(
             [&](double u) { return evaluate_transfer(tf.data(), int(tf.size()), d(u)).sigma; },
             0.0, 1.0, 1e-13)
      .value;
}

TEST(VolumeChord, CellCubicIsTheTrilinearInterpolant) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    GridCell cell;
    for (double& c : cell.corner) c = unit(rng);
    double f0[3], f1[3];
    for (int a = 0; a < 3; ++a) f0[a] = unit(rng), f1[a] = unit(rng);
    const Cubic d = cell_density_cubic(cell.corner, f0, f1);
    for (double u : {0.0, 0.2, 0.5, 0.77, 1.0}) {
      for (int a = 0; a < 3; ++a) cell.f[a] = f0[a] + (f1[a] - f0[a]) * u;
      EXPECT_NEAR(d(u), trilinear(cell), 1e-14) << trial << " " << u;
    }
  }
}

TEST(VolumeChord, TransferIntegralOfACubicMatchesAdaptiveSimpson) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 300; ++trial) {
    // 1 to 6 control points; every fifth function has a step (two points at one density).
    const int n = 1 + trial % 6;
    std::vector<double> densities;
    for (int k = 0; k < n; ++k) densities.push_back(unit(rng));
    std::sort(densities.begin(), densities.end());
    if (trial % 5 == 0 && n >= 2) densities[1] = densities[0];
    std::vector<TransferPoint> tf;
    for (double x : densities) tf.push_back(tp(x, 8.0 * unit(rng)));
    double corner[8], f0[3], f1[3];
    for (double& c : corner) c = unit(rng);
    for (int a = 0; a < 3; ++a) f0[a] = unit(rng), f1[a] = unit(rng);
    const Cubic d = cell_density_cubic(corner, f0, f1);
    EXPECT_NEAR(transfer_integral_of_cubic(tf.data(), n, d), simpson_reference(tf, d), 1e-10)
        << trial;
  }
}

TEST(VolumeChord, CellsWhoseCornersSpanNoControlPointTakeTheCubicsMean) {
  // Corners in a narrow band: every other cell's band holds no control point (the shortcut),
  // the rest hold one (the cuts); both against adaptive Simpson, and constant cells exactly.
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const std::vector<TransferPoint> tf = {tp(0.2, 0.0), tp(0.5, 6.0), tp(0.5, 2.0), tp(0.9, 9.0)};
  int shortcut = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const double base = unit(rng), width = 0.1 * unit(rng);
    double corner[8], f0[3], f1[3];
    for (double& c : corner) c = base + width * unit(rng);
    for (int a = 0; a < 3; ++a) f0[a] = unit(rng), f1[a] = unit(rng);
    const double lo = *std::min_element(corner, corner + 8);
    const double hi = *std::max_element(corner, corner + 8);
    shortcut += std::none_of(tf.begin(), tf.end(), [&](const TransferPoint& p) {
      return p.density > lo && p.density < hi;
    });
    EXPECT_NEAR(cell_transfer_integral(tf.data(), 4, corner, f0, f1),
                simpson_reference(tf, cell_density_cubic(corner, f0, f1)), 1e-10)
        << trial;
  }
  EXPECT_GT(shortcut, 200);
  const double flat[8] = {0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5}, f[3] = {0.3, 0.3, 0.3};
  EXPECT_DOUBLE_EQ(cell_transfer_integral(tf.data(), 4, flat, f, f),
                   evaluate_transfer(tf.data(), 4, 0.5).sigma);
}

TEST(VolumeChord, TurningPointsCrossTheSameControlPointThreeTimes) {
  // d(u) = 0.5 + 3u - 9u^2 + 6u^3 turns at u = 0.211 (d = 0.789) and u = 0.789 (d = 0.211), so a
  // kink at 0.5 is crossed three times, and kinks at 0.25 and 0.75 twice each.
  const Cubic d{{0.5, 3.0, -9.0, 6.0}};
  const std::vector<TransferPoint> tf = {tp(0.25, 0.0), tp(0.5, 4.0), tp(0.75, 1.0)};
  EXPECT_NEAR(transfer_integral_of_cubic(tf.data(), 3, d), simpson_reference(tf, d), 1e-10);
  // A constant density and a linear one: closed forms.
  const Cubic flat{{0.6, 0.0, 0.0, 0.0}};
  EXPECT_NEAR(transfer_integral_of_cubic(tf.data(), 3, flat), 4.0 - 3.0 * 0.1 / 0.25, 1e-14);
  const Cubic ramp{{0.0, 1.0, 0.0, 0.0}};  // sigma integral over [0, 1] of the transfer
  const double expected = 0.25 * (0.0 + 4.0) / 2.0 + 0.25 * (4.0 + 1.0) / 2.0 + 0.25 * 1.0;
  EXPECT_NEAR(transfer_integral_of_cubic(tf.data(), 3, ramp), expected, 1e-14);
}

TEST(VolumeChord, EmptyBricksAreCrossedWithoutChangingTheAnswer) {
  // A 40 x 33 x 27 grid, zero except for blobs; extinction zero below density 0.3, so most
  // bricks are flagged empty. The walk with the flags equals the walk with none flagged, and
  // both the independent integral. (Ray 163 once lost four cell faces: the ray stood on a
  // face by rounding, and the walk took the next face to be behind it.)
  test::SceneBuilder b;
  VolumeGrid g;
  g.name = "blobs";
  g.dims = {40, 33, 27};
  g.spacing = dvec3(0.05);
  g.origin = dvec3(-1.0, -0.8, -0.65);
  for (int z = 0; z < g.dims.z; ++z)
    for (int y = 0; y < g.dims.y; ++y)
      for (int x = 0; x < g.dims.x; ++x) {
        const double r1 = glm::length(dvec3(x - 10, y - 20, z - 8)) / 6.0;
        const double r2 = glm::length(dvec3(x - 30, y - 9, z - 19)) / 5.0;
        g.density.push_back(float(std::max({0.0, 1.0 - r1, 0.9 - r2})));
      }
  b.scene.volumes.push_back(g);
  const Aabb box = g.bounds();
  Object& o = b.add(make_box(box.lo, box.hi), 0.0, InteriorKind::volume);
  o.interior.volume = 0;
  o.interior.transfer.points = {tp(0.3, 0.0), tp(0.6, 6.0), tp(1.0, 9.0)};
  b.omni({0.0, 2.0, 0.0});
  const SceneData data = b.build();
  const SceneView& s = data.view();
  int64_t flagged = 0;
  for (int64_t i = 0; i < s.brick_empty.size; ++i) flagged += s.brick_empty[i];
  ASSERT_GT(flagged, s.brick_empty.size / 3);
  const std::vector<uint8_t> none(size_t(s.brick_empty.size), 0);
  SceneView unflagged = s;
  unflagged.brick_empty = {none.data(), s.brick_empty.size};
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int nonzero = 0;
  for (int ray = 0; ray < 400; ++ray) {
    const dvec3 a = box.lo + (box.hi - box.lo) * dvec3(unit(rng), unit(rng), unit(rng));
    const dvec3 c = box.lo + (box.hi - box.lo) * dvec3(unit(rng), unit(rng), unit(rng));
    const dvec3 dir = glm::normalize(c - a);
    // From outside the box (clamped region) to past its far side.
    const double with = volume_optical_depth(s, s.objects[0], a, dir, -0.5, 3.0);
    const double without = volume_optical_depth(unflagged, s.objects[0], a, dir, -0.5, 3.0);
    EXPECT_NEAR(with, without, 1e-12 * (1.0 + without)) << ray;
    // And both against adaptive Simpson on the trilinear extinction itself (an independent
    // integral: it knows nothing of cells, cubics or bricks), started on 700 stretches of 0.005,
    // a tenth of a cell, so that its first samples cannot all miss a blob.
    double independent = 0.0;
    for (int k = 0; k < 700; ++k) {
      independent += test::adaptive_simpson(
                         [&](double t) { return volume_sigma(s, s.objects[0], a + dir * t); },
                         -0.5 + 0.005 * k, -0.5 + 0.005 * (k + 1), 1e-15)
                         .value;
    }
    EXPECT_NEAR(without, independent, 1e-9) << ray;
    nonzero += without > 0.0;
  }
  EXPECT_GT(nonzero, 40);
}

}  // namespace
}  // namespace dv
