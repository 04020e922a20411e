// The oracle through glass and tinted media, per colour channel: a red glass slab casts a
// partial red shadow ((1 - F) c per crossing, F = 0.04 at normal incidence for ior 1.5), a
// tinted constant medium absorbs each channel by its own extinction, the scalar answer is the
// luminance, and a grey scene's answer is what it always was (1 - alpha per crossing).
#include <cmath>

#include <gtest/gtest.h>

#include "engine/oracle/transmittance.h"
#include "render/load/mesh_generators.h"
#include "tests/support/scene_builder.h"

namespace dv {
namespace {

using test::SceneBuilder;

OracleResult exact_below(SceneBuilder& b, const dvec3& p) {
  b.spot({p.x, 3.0, p.z}, {0.0, -1.0, 0.0}, 30.0);
  const SceneData data = b.build();
  const OracleResult r = exact_transmittance(data.view(), data.view().lights[0], p);
  EXPECT_EQ(r.flags, 0u);
  return r;
}

TEST(OracleGlass, RedGlassSlabCastsAPartialRedShadow) {
  SceneBuilder b;
  Object& slab = b.add(make_box({-1.0, 1.0, -1.0}, {1.0, 1.2, 1.0}), 0.0);
  slab.material.transmission = 1.0;
  slab.material.color = {1.0, 0.2, 0.2};
  const OracleResult r = exact_below(b, {0.1, 0.0, 0.05});
  const dvec3 crossing = 0.96 * dvec3(1.0, 0.2, 0.2);  // straight down: F = 0.04
  EXPECT_NEAR(r.rgb.x, crossing.x * crossing.x, 1e-12);
  EXPECT_NEAR(r.rgb.y, crossing.y * crossing.y, 1e-12);
  EXPECT_NEAR(r.rgb.z, crossing.z * crossing.z, 1e-12);
  EXPECT_NEAR(r.transmittance, 0.2126 * r.rgb.x + 0.7152 * r.rgb.y + 0.0722 * r.rgb.z, 1e-15);
}

TEST(OracleGlass, AnIndexOfOneReflectsNothingAtNormalIncidence) {
  SceneBuilder b;
  Object& pane = b.add(make_box({-1.0, 1.0, -1.0}, {1.0, 1.2, 1.0}), 0.0);
  pane.material.transmission = 1.0;
  pane.material.color = dvec3(1.0);
  pane.material.ior = 1.0;
  EXPECT_NEAR(exact_below(b, {0.0, 0.0, 0.0}).transmittance, 1.0, 1e-15);
}

TEST(OracleGlass, TintedMediumAbsorbsEachChannelByItsOwnExtinction) {
  SceneBuilder b;
  Object& box = b.add(make_box({-1.0, 1.0, -1.0}, {1.0, 1.5, 1.0}), 0.0, InteriorKind::constant);
  const dvec3 sigma(0.2, 1.0, 3.0);
  box.interior.sigma = (sigma.x + sigma.y + sigma.z) / 3.0;
  box.interior.sigma_tint = sigma / box.interior.sigma;
  const OracleResult r = exact_below(b, {0.0, 0.0, 0.0});
  EXPECT_NEAR(r.rgb.x, std::exp(-sigma.x * 0.5), 1e-12);
  EXPECT_NEAR(r.rgb.y, std::exp(-sigma.y * 0.5), 1e-12);
  EXPECT_NEAR(r.rgb.z, std::exp(-sigma.z * 0.5), 1e-12);
}

TEST(OracleGlass, GlassAroundATintedMediumAddsOnlyFresnelAtItsSurfaces) {
  SceneBuilder b;
  Object& vessel = b.add(make_box({-1.0, 1.0, -1.0}, {1.0, 1.5, 1.0}), 0.0, InteriorKind::constant);
  vessel.material.transmission = 1.0;
  vessel.material.color = {0.1, 0.1, 1.0};  // ignored: the medium colours
  vessel.interior.sigma = 1.0;
  vessel.interior.sigma_tint = {0.5, 1.0, 1.5};
  const OracleResult r = exact_below(b, {0.0, 0.0, 0.0});
  EXPECT_NEAR(r.rgb.x, 0.96 * 0.96 * std::exp(-0.25), 1e-12);
  EXPECT_NEAR(r.rgb.z, 0.96 * 0.96 * std::exp(-0.75), 1e-12);
}

TEST(OracleGlass, GreySceneAnswersAreUnchanged) {
  SceneBuilder b;
  b.add(make_box({-1.0, 1.0, -1.0}, {1.0, 1.2, 1.0}), 0.5);
  b.add(make_box({-1.0, 1.5, -1.0}, {1.0, 1.7, 1.0}), 0.0, InteriorKind::constant, 0.7);
  const OracleResult r = exact_below(b, {0.0, 0.0, 0.0});
  const double expected = 0.5 * 0.5 * std::exp(-0.7 * 0.2);
  EXPECT_EQ(r.rgb.x, r.rgb.y);
  EXPECT_EQ(r.rgb.y, r.rgb.z);
  EXPECT_EQ(r.transmittance, r.rgb.x);
  EXPECT_NEAR(r.transmittance, expected, 1e-14);
}

}  // namespace
}  // namespace dv
