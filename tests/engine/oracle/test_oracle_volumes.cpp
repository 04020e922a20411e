// Oracle through density volumes against closed forms (linear ramps, transfer-function kinks,
// transformed grids) and against brute-force midpoint integration on random grids.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "engine/oracle/transmittance.h"
#include "tests/support/scene_builder.h"

namespace dv {
namespace {

using test::SceneBuilder;
constexpr auto oracle = test::oracle_at;

// A ramp volume: density = i / (n - 1) along x, n x 2 x 2 samples of spacing h, and a box mesh
// that covers the grid exactly.
Object& add_ramp(SceneBuilder& b, int n, double h, std::vector<TransferPoint> transfer) {
  VolumeGrid g;
  g.name = "ramp";
  g.dims = {n, 2, 2};
  g.spacing = dvec3(h);
  for (int z = 0; z < 2; ++z)
    for (int y = 0; y < 2; ++y)
      for (int x = 0; x < n; ++x) g.density.push_back(float(double(x) / (n - 1)));
  b.scene.volumes.push_back(g);
  Object& o = b.add(make_box({0, 0, 0}, {(n - 1) * h, h, h}), 0.0, InteriorKind::volume);
  o.interior.volume = int(b.scene.volumes.size()) - 1;
  o.interior.transfer.points = std::move(transfer);
  return o;
}

TransferPoint tp(double density, double sigma) {
  return {density, dvec3(1.0), sigma};
}

TEST(OracleVolumes, LinearRampIsExact) {
  SceneBuilder b;
  const int n = 9;
  const double h = 0.25, k = 3.0, L = (n - 1) * h;
  add_ramp(b, n, h, {tp(0.0, 0.0), tp(1.0, k)});
  b.omni({-1.0, 0.5 * h, 0.5 * h});
  const SceneData data = b.build();
  for (double x : {0.3, 1.0, 1.77, 2.0}) {  // points inside the volume
    const double tau = k * x * x / (2.0 * L);
    EXPECT_NEAR(oracle(data, 0, {x, 0.5 * h, 0.5 * h}), std::exp(-tau), 1e-9) << x;
  }
  EXPECT_NEAR(oracle(data, 0, {5.0, 0.5 * h, 0.5 * h}), std::exp(-k * L / 2.0), 1e-9);
}

TEST(OracleVolumes, TransferFunctionKink) {
  SceneBuilder b;
  // Densities i/4 are exact in float; the kink at density 0.6 lies inside cell [1.0, 1.5].
  const int n = 5;
  const double h = 0.5, k = 2.0, L = (n - 1) * h;
  add_ramp(b, n, h, {tp(0.0, 0.0), tp(0.6, 0.0), tp(1.0, k)});
  b.omni({-1.0, 0.2, 0.2});
  const SceneData data = b.build();
  for (double x : {0.5, 1.1, 1.2, 1.35, 1.9}) {
    const double tau = x <= 0.6 * L ? 0.0 : k / 0.4 * (x * x / (2.0 * L) - 0.6 * x + 0.18 * L);
    EXPECT_NEAR(oracle(data, 0, {x, 0.2, 0.2}), std::exp(-tau), 1e-9) << x;
  }
}

TEST(OracleVolumes, TransformedGrid) {
  // The ramp rotated 90 degrees about y and scaled 2x: grid x runs along world -z (z in [-4, 0]),
  // grid z along world +x (x in [0, 1]), y in [0, 1].
  SceneBuilder b;
  const int n = 5;
  const double h = 0.5, k = 1.5, L = 2.0 * (n - 1) * h;
  Object& o = add_ramp(b, n, h, {tp(0.0, 0.0), tp(1.0, k)});
  o.transform = glm::dmat4(glm::dmat3(0, 0, -2, 0, 2, 0, 2, 0, 0));
  b.omni({0.5, 0.5, 1.0});  // in front of the ramp's low end at z = 0
  const SceneData data = b.build();
  for (double depth : {0.7, 1.3, 3.1}) {  // distance travelled inside, from the low end
    const double tau = k * depth * depth / (2.0 * L);
    EXPECT_NEAR(oracle(data, 0, {0.5, 0.5, -depth}), std::exp(-tau), 1e-9) << depth;
  }
}

TEST(OracleVolumes, RandomGridMatchesBruteForce) {
  SceneBuilder b;
  VolumeGrid g;
  g.name = "random";
  g.dims = {7, 5, 6};
  g.spacing = {0.3, 0.35, 0.25};
  g.origin = {-0.9, -0.7, -0.625};
  std::mt19937 rng(42);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int64_t i = 0; i < g.voxel_count(); ++i) g.density.push_back(u(rng));
  b.scene.volumes.push_back(g);
  const Aabb box = g.bounds();
  Object& o = b.add(make_box(box.lo, box.hi), 0.0, InteriorKind::volume);
  o.interior.volume = 0;
  o.interior.transfer.points = {tp(0.0, 0.5), tp(0.3, 0.2), tp(0.31, 2.5), tp(1.0, 4.0)};
  b.omni({2.0, 1.5, 1.0});
  const SceneData data = b.build();
  const SceneView& s = data.view();
  const ObjectView& ov = s.objects[0];
  for (const dvec3 p : {dvec3(-0.2, 0.1, 0.05), dvec3(-2.0, -1.5, -1.0), dvec3(0.5, -0.6, -0.5)}) {
    // Brute force: midpoint rule over the part of the segment inside the grid box.
    const dvec3 a = s.lights[0].position;
    const int steps = 400000;
    double tau = 0.0;
    for (int i = 0; i < steps; ++i) {
      const dvec3 x = a + (p - a) * ((i + 0.5) / steps);
      if (box.contains(x)) tau += volume_sigma(s, ov, x);
    }
    tau *= glm::length(p - a) / steps;
    EXPECT_NEAR(oracle(data, 0, p), std::exp(-tau), 2e-6) << p.x;
  }
}

}  // namespace
}  // namespace dv
