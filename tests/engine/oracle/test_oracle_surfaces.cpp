// Oracle against closed forms: translucent surfaces, constant interiors, slabs, lights inside
// media, spot cones, directional lights, points on surfaces and rays through shared edges.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/oracle/transmittance.h"
#include "tests/support/scene_builder.h"

namespace dv {
namespace {

using test::SceneBuilder;
constexpr auto oracle = test::oracle_at;

TEST(OracleSurfaces, TranslucentQuadsMultiply) {
  SceneBuilder b;
  const double alphas[] = {0.25, 0.5, 0.1};
  for (int i = 0; i < 3; ++i) {
    Object& o = b.add(make_quad(4.0), alphas[i]);
    o.transform[3] = dvec4(0.0, 1.0 + i, 0.0, 1.0);
  }
  b.omni({0.1, 10.0, 0.2});
  const SceneData data = b.build();
  EXPECT_NEAR(oracle(data, 0, {0.0, 0.0, 0.0}), 0.75 * 0.5 * 0.9, 1e-15);
  EXPECT_NEAR(oracle(data, 0, {0.0, 2.5, 0.0}), 0.9, 1e-15);
  EXPECT_DOUBLE_EQ(oracle(data, 0, {0.0, 5.0, 0.0}), 1.0);
}

TEST(OracleSurfaces, PointOnSurfaceIsNotShadowedByIt) {
  // Convention: a crossing at the point itself is not between light and point.
  SceneBuilder b;
  b.add(make_box({-1, -1, -1}, {1, 1, 1}), 1.0);
  b.omni({0.3, 5.0, 0.2});
  const SceneData data = b.build();
  EXPECT_DOUBLE_EQ(oracle(data, 0, {0.1, 1.0, -0.2}), 1.0);   // on the lit top face
  EXPECT_DOUBLE_EQ(oracle(data, 0, {0.1, -1.0, -0.2}), 0.0);  // on the bottom face: top between
}

TEST(OracleSurfaces, SharedEdgeIsCrossedOnce) {
  // The ray runs exactly through the diagonals that split the box's top and bottom faces.
  SceneBuilder b;
  b.add(make_box({-1, -1, -1}, {1, 1, 1}), 0.5);
  b.omni({0.0, 5.0, 0.0});
  b.omni({0.5, 5.0, 0.5});
  const SceneData data = b.build();
  EXPECT_DOUBLE_EQ(oracle(data, 0, {0.0, -5.0, 0.0}), 0.25);
  EXPECT_DOUBLE_EQ(oracle(data, 1, {0.5, -5.0, 0.5}), 0.25);
  EXPECT_DOUBLE_EQ(oracle(data, 0, {0.0, 0.0, 0.0}), 0.5);
}

TEST(OracleSurfaces, StackedSlabsOfConstantExtinction) {
  SceneBuilder b;
  const double sigma[] = {0.7, 1.3, 0.2};
  const double lo[] = {0.0, 1.0, 3.0}, hi[] = {0.5, 2.5, 3.25};
  for (int i = 0; i < 3; ++i)
    b.add(make_box({-2, lo[i], -2}, {2, hi[i], 2}), 0.0, InteriorKind::constant, sigma[i]);
  b.omni({0.0, 10.0, 0.0});
  b.directional({0.0, -1.0, 0.0});
  const SceneData data = b.build();
  const double all = 0.7 * 0.5 + 1.3 * 1.5 + 0.2 * 0.25;
  EXPECT_NEAR(oracle(data, 0, {0.0, -1.0, 0.0}), std::exp(-all), 1e-14);
  EXPECT_NEAR(oracle(data, 1, {0.3, -1.0, 0.1}), std::exp(-all), 1e-14);
  // Point inside the middle slab: 0.7 of its 1.5 lie above the point.
  EXPECT_NEAR(oracle(data, 0, {0.0, 1.8, 0.0}), std::exp(-(1.3 * 0.7 + 0.2 * 0.25)), 1e-14);
}

TEST(OracleSurfaces, OverlappingMediaAdd) {
  SceneBuilder b;
  b.add(make_box({-1, 0, -1}, {1, 2, 1}), 0.0, InteriorKind::constant, 0.5);
  b.add(make_box({-1, 1, -1}, {1, 3, 1}), 0.0, InteriorKind::constant, 2.0);
  b.omni({0.0, 10.0, 0.0});
  const SceneData data = b.build();
  EXPECT_NEAR(oracle(data, 0, {0.0, -1.0, 0.0}), std::exp(-(0.5 * 2.0 + 2.0 * 2.0)), 1e-14);
}

TEST(OracleSurfaces, LightInsideAMedium) {
  SceneBuilder b;
  b.add(make_box({-1, -1, -1}, {1, 1, 1}), 0.4, InteriorKind::constant, 1.5);
  b.omni({0.0, 0.5, 0.0});
  const SceneData data = b.build();
  EXPECT_NEAR(oracle(data, 0, {0.0, -0.25, 0.0}), std::exp(-1.5 * 0.75), 1e-14);
  EXPECT_NEAR(oracle(data, 0, {0.0, -3.0, 0.0}), 0.6 * std::exp(-1.5 * 1.5), 1e-14);
}

TEST(OracleSurfaces, ConstantExtinctionSphereChord) {
  // A finely tessellated sphere: T = exp(-sigma * chord) up to the tessellation error.
  SceneBuilder b;
  const double r = 1.0, sigma = 0.8;
  b.add(make_icosphere(r, 6), 0.0, InteriorKind::constant, sigma);
  b.omni({0.0, 0.0, 5.0});
  const SceneData data = b.build();
  for (double offset : {0.0, 0.3, 0.6, 0.9}) {
    const dvec3 p(offset, 0.0, -5.0);
    // The ray from (0,0,5) to p passes at distance d from the centre.
    const dvec3 dir = glm::normalize(p - dvec3(0, 0, 5));
    const dvec3 closest = dvec3(0, 0, 5) + dir * glm::dot(-dvec3(0, 0, 5), dir);
    const double d = glm::length(closest);
    const double chord = 2.0 * std::sqrt(r * r - d * d);
    EXPECT_NEAR(oracle(data, 0, p), std::exp(-sigma * chord), 2e-3) << "offset " << offset;
  }
}

TEST(OracleSurfaces, SpotConeAndDirectional) {
  SceneBuilder b;
  b.add(make_quad(2.0), 0.5);
  b.spot({0.0, 5.0, 0.0}, {0.0, -1.0, 0.0}, 20.0);
  b.directional({1.0, -1.0, 0.0});
  const SceneData data = b.build();
  EXPECT_DOUBLE_EQ(oracle(data, 0, {0.0, -1.0, 0.0}), 0.5);
  EXPECT_DOUBLE_EQ(oracle(data, 0, {4.0, -1.0, 0.0}), 0.0);  // outside the cone
  // The directional light shines along (1,-1,0): rays toward it go up and to -x.
  EXPECT_DOUBLE_EQ(oracle(data, 1, {0.0, -0.5, 0.0}), 0.5);   // ray meets y=0 at x=-0.5: quad
  EXPECT_DOUBLE_EQ(oracle(data, 1, {-0.5, -3.0, 0.0}), 1.0);  // ray passes x=-3.5 at y=0: misses
}

TEST(OracleSurfaces, OpaqueCasterGivesZeroAndOutsideIsLit) {
  SceneBuilder b;
  b.add(make_box({-1, -1, -1}, {1, 1, 1}), 1.0);
  b.omni({0.0, 5.0, 0.0});
  const SceneData data = b.build();
  EXPECT_DOUBLE_EQ(oracle(data, 0, {0.0, -2.0, 0.0}), 0.0);
  EXPECT_DOUBLE_EQ(oracle(data, 0, {3.0, -2.0, 0.0}), 1.0);
}

}  // namespace
}  // namespace dv
