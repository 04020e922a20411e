// The crossing rule (engine/scene/surface_transmittance.h): surfaces without transmission pass
// exactly 1 - alpha, glass passes (1 - Fresnel) times its colour (white with an interior), the
// coverage argument scales both, luminance leaves grey values bit for bit, and glass tints
// where its factor or its base-colour texture has colour.
#include <cmath>

#include <gtest/gtest.h>

#include "engine/scene/surface_transmittance.h"

namespace dv {
namespace {

ObjectView glass(const dvec3& color, InteriorKind interior = InteriorKind::none) {
  ObjectView o{};
  o.color = color;
  o.alpha = 0.0;
  o.transmission = 1.0;
  o.ior = 1.5;
  o.interior = interior;
  return o;
}

TEST(SurfaceTransmittance, WithoutTransmissionIsOneMinusAlphaExactly) {
  ObjectView o{};
  o.alpha = 0.3;
  o.color = dvec3(1.0, 0.0, 0.0);
  const dvec3 t = surface_transmittance(o, 0.2, material_coverage(o), o.color);
  EXPECT_EQ(t, dvec3(1.0 - 0.3));
  EXPECT_FALSE(tints_light(o));
}

TEST(SurfaceTransmittance, SchlickFresnelAtNormalAndGrazingIncidence) {
  EXPECT_NEAR(fresnel_schlick(1.5, 1.0), 0.04, 1e-15);
  EXPECT_NEAR(fresnel_schlick(1.5, -1.0), 0.04, 1e-15);  // either side of the surface
  EXPECT_NEAR(fresnel_schlick(1.5, 0.0), 1.0, 1e-15);
  EXPECT_NEAR(fresnel_schlick(1.0, 0.7), 0.0 + std::pow(0.3, 5.0), 1e-15);
}

TEST(SurfaceTransmittance, ThinGlassPassesOneMinusFresnelTimesItsColour) {
  const ObjectView red = glass({1.0, 0.25, 0.25});
  const dvec3 t = surface_transmittance(red, -1.0, material_coverage(red), red.color);
  EXPECT_NEAR(t.x, 0.96, 1e-15);
  EXPECT_NEAR(t.y, 0.96 * 0.25, 1e-15);
  EXPECT_NEAR(t.z, 0.96 * 0.25, 1e-15);
  EXPECT_TRUE(tints_light(red));
  // Half the surface covered (a texture's alpha): the uncovered half passes untouched.
  const dvec3 half = surface_transmittance(red, 1.0, 0.5, red.color);
  EXPECT_NEAR(half.y, 0.5 + 0.5 * 0.96 * 0.25, 1e-15);
  // Grazing: Fresnel reflects nearly everything.
  EXPECT_LT(surface_transmittance(red, 0.01, 1.0, red.color).x, 0.1);
}

TEST(SurfaceTransmittance, GreyGlassTintsWhereItsTextureHasColour) {
  ObjectView pane = glass({1.0, 1.0, 1.0});
  pane.texture = -1;
  EXPECT_FALSE(tints_light(pane));
  pane.texture = 0;
  EXPECT_FALSE(tints_light(pane));  // a grey texture
  pane.texture_colour = true;
  EXPECT_TRUE(tints_light(pane));
  pane.texture = -1;  // the flag means nothing without a texture
  EXPECT_FALSE(tints_light(pane));
  pane.texture = 0;
  pane.transmission = 0.0;  // an opaque surface tints nothing, whatever its texture
  pane.alpha = 1.0;
  EXPECT_FALSE(tints_light(pane));
}

TEST(SurfaceTransmittance, GlassAroundAMediumAddsOnlyFresnel) {
  const ObjectView vessel = glass({1.0, 0.25, 0.25}, InteriorKind::constant);
  const dvec3 t = surface_transmittance(vessel, 1.0, material_coverage(vessel), vessel.color);
  EXPECT_NEAR(t.x, 0.96, 1e-15);
  EXPECT_NEAR(t.y, 0.96, 1e-15);
  EXPECT_FALSE(tints_light(vessel));  // its grey medium (sigma_rgb 0) does not tint either
}

TEST(SurfaceTransmittance, LuminanceKeepsGreyBitForBit) {
  for (double v : {0.1, 1.0 / 3.0, 0.7, 0.123456789}) EXPECT_EQ(luminance(dvec3(v)), v);
  EXPECT_NEAR(luminance({1.0, 0.0, 0.0}), 0.2126, 1e-15);
  EXPECT_NEAR(luminance({0.0, 1.0, 0.0}), 0.7152, 1e-15);
}

}  // namespace
}  // namespace dv
