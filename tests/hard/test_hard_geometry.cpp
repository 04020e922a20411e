// Hard geometry for the exact oracle and deep shadow maps, on the CPU and CUDA, each against a
// closed form: two translucent slabs far from the origin (1e4, 1e5) and a thousand times
// smaller than usual (1e-3), a light inside a translucent closed mesh and inside a constant
// medium, duplicate triangles (two coincident surfaces: both count), zero-area triangles (no
// crossing), and 300 surfaces on one texel. Grazing light, the camera inside a medium, near
// plane crossings, huge and degenerate triangles and non-manifold or open meshes are the tests
// of tests/render/frame, tests/strategies/shadow, tests/engine/raster, tests/engine/scene,
// tests/render/io and tests/render/load labelled hard there.
#include <gtest/gtest.h>

#include <cmath>

#include "tests/hard/hard_test_support.h"

namespace dv::test {
namespace {

class HardGeometry : public HardOnBackends {
 protected:
  // Oracle (CPU) and DSM (this backend, nearest) at every point against `expected`; the DSM
  // within `tolerance`.
  void expect_transmittance(const Scene& scene, const std::vector<dvec3>& points,
                            const std::vector<double>& expected, float eps, double tolerance,
                            int res = 16) {
    Scene host_scene = scene;
    validate_scene(host_scene);
    const SceneData host(host_scene, Memory::host);
    for (size_t i = 0; i < points.size(); ++i)
      EXPECT_NEAR(oracle_at(host, 0, points[i]), expected[i], 1e-9 * (1.0 + expected[i]))
          << "oracle, point " << i;
    const HardMaps m = generate_maps(scene, GetParam(), unbiased_settings(eps, res));
    const std::vector<double> got = dsm_lookups(m, GetParam(), points, 0);
    for (size_t i = 0; i < points.size(); ++i)
      EXPECT_NEAR(got[i], expected[i], tolerance) << "dsm, point " << i;
  }
};

// Quads of alpha 0.3 at y = 1 and 0.5 at y = 0 (size 4) under a spot at y = 5, scaled by s
// and moved by o: T = 1 above both, 0.7 between, 0.35 below.
TEST_P(HardGeometry, FarFromTheOriginAndTiny) {
  struct Placement {
    double scale;
    dvec3 offset;
  };
  for (const Placement& at : {Placement{1.0, dvec3(0.0)}, Placement{1.0, dvec3(1e4, -2e4, 3e4)},
                              Placement{1.0, dvec3(1e5, 1e5, -1e5)}, Placement{1e-3, dvec3(0.0)},
                              Placement{1e-3, dvec3(0.5, 0.5, 0.5)}}) {
    SCOPED_TRACE("scale " + std::to_string(at.scale) + " offset " + std::to_string(at.offset.x));
    SceneBuilder b;
    for (auto [height, alpha] : {std::pair{1.0, 0.3}, std::pair{0.0, 0.5}}) {
      TriangleMesh q = quad_at(height, 4.0);
      for (dvec3& v : q.positions) v = v * at.scale + at.offset;
      b.add(std::move(q), alpha);
    }
    b.spot(dvec3(0.0, 5.0, 0.0) * at.scale + at.offset, dvec3(0.0, -1.0, 0.0), 25.0);
    std::vector<dvec3> points;
    std::vector<double> expected;
    for (auto [y, t] : {std::pair{2.0, 1.0}, std::pair{0.5, 0.7}, std::pair{-1.0, 0.35}})
      for (double x : {-0.7, 0.0, 0.45}) {
        points.push_back(dvec3(x, y, 0.3 - x) * at.scale + at.offset);
        expected.push_back(t);
      }
    expect_transmittance(b.scene, points, expected, 0.01f, 0.01 + 1e-6);
  }
}

// An omni light at the centre of a closed translucent box (alpha 0.4, no interior): every
// point outside is behind exactly one crossing, T = 0.6; points inside are lit.
TEST_P(HardGeometry, LightInsideATranslucentClosedMesh) {
  SceneBuilder b;
  b.add(make_box(dvec3(-1.0), dvec3(1.0)), 0.4);
  b.omni(dvec3(0.1, -0.2, 0.05));
  const std::vector<dvec3> points = {{3, 0, 0}, {0, -3, 0},      {0, 0, 3},     {-2, 2, -2},
                                     {2, 2, 2}, {0.5, 0.5, 0.5}, {-0.5, 0, 0.7}};
  expect_transmittance(b.scene, points, {0.6, 0.6, 0.6, 0.6, 0.6, 1.0, 1.0}, 0.01f, 0.01 + 1e-6);
}

// An omni light inside a box of constant extinction sigma = 0.7 (surfaces of alpha 0): T =
// exp(-sigma d), d the part of the segment inside. The DSM samples the medium's exponential,
// so its bound is 1.5 eps (tests/engine/dsm's rule for media).
TEST_P(HardGeometry, LightInsideAConstantMedium) {
  SceneBuilder b;
  b.add(make_box(dvec3(-1.0), dvec3(1.0)), 0.0, InteriorKind::constant, 0.7);
  b.omni(dvec3(0.0));
  const std::vector<dvec3> points = {{0, 0, 2.5}, {-3, 0, 0}, {0, 0.5, 0}, {2, 0.3, 0.2}};
  const std::vector<double> expected = {std::exp(-0.7), std::exp(-0.7), std::exp(-0.35),
                                        std::exp(-0.7 * 0.5 * std::sqrt(4.13))};
  expect_transmittance(b.scene, points, expected, 0.01f, 1.5 * 0.01 + 1e-5);
}

// The same quad twice (two objects of alpha 0.5) is two surfaces: T = 0.25 behind both. A
// zero-area triangle (three collinear corners) in a mesh is crossed by no ray.
TEST_P(HardGeometry, DuplicateAndZeroAreaTriangles) {
  SceneBuilder b;
  b.add(quad_at(1.0, 4.0), 0.5);
  b.add(quad_at(1.0, 4.0), 0.5);
  TriangleMesh sliver;
  sliver.positions = {{-1.0, 0.5, 0.0}, {0.0, 0.5, 0.0}, {1.0, 0.5, 0.0}};
  sliver.triangles = {{0u, 1u, 2u}};
  b.add(std::move(sliver), 1.0);
  b.spot(dvec3(0.0, 5.0, 0.0), dvec3(0.0, -1.0, 0.0), 30.0);
  const std::vector<dvec3> points = {{0.0, 0.0, 0.0}, {0.5, -1.0, 0.0}, {0.0, 2.0, 0.0}};
  expect_transmittance(b.scene, points, {0.25, 0.25, 1.0}, 0.0f, 1e-6);
}

// 300 quads of alpha 0.02 stacked 0.001 apart across the spot's axis, the centre ray of the
// middle texel of a 5 x 5 map: T = 0.98^k behind k of them; with eps = 0 every crossing is a
// twin, 600 nodes in that texel.
TEST_P(HardGeometry, ThreeHundredSurfacesOnOneTexel) {
  SceneBuilder b;
  for (int k = 0; k < 300; ++k) b.add(quad_at(1.0 + 0.001 * k, 4.0), 0.02);
  b.spot(dvec3(0.0, 5.0, 0.0), dvec3(0.0, -1.0, 0.0), 20.0);
  const std::vector<dvec3> points = {{0.0, 0.5, 0.0}, {0.0, 1.1505, 0.0}, {0.0, 1.5, 0.0}};
  const std::vector<double> expected = {std::pow(0.98, 300), std::pow(0.98, 149), 1.0};
  expect_transmittance(b.scene, points, expected, 0.0f, 1e-5, 5);
}

INSTANTIATE_TEST_SUITE_P(Backends, HardGeometry, ::testing::Values(Backend::cpu, Backend::cuda),
                         BackendName());

}  // namespace
}  // namespace dv::test
