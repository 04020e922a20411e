// What `--explain` says each shadow method drops of a scene's effects (effect_losses.h): the
// effects are found from the materials and interiors, each named once with its count, and the
// text for a method is its entry of the table.
#include <gtest/gtest.h>

#include <string>

#include "render/load/mesh_generators.h"
#include "strategies/shadow/effect_losses.h"
#include "tests/support/scene_builder.h"

namespace dv {
namespace {

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// An opaque floor, two translucent panels, a grey and a blue medium, red glass and a volume.
Scene effects_scene() {
  test::SceneBuilder b;
  b.add(make_box({-2, -0.1, -2}, {2, 0, 2}));
  b.add(make_quad(1.0), 0.5);
  b.add(make_quad(0.5), 0.3);
  b.add(make_box({0, 0, 0}, {1, 1, 1}), 0.0, InteriorKind::constant, 1.0);
  Object& blue = b.add(make_box({1, 0, 0}, {2, 1, 1}), 0.0, InteriorKind::constant, 2.0);
  blue.interior.sigma_tint = {1.5, 1.2, 0.3};
  Object& glass = b.add(make_box({-1, 0, 0}, {0, 1, 1}), 0.0);
  glass.material.transmission = 1.0;
  glass.material.color = {1.0, 0.1, 0.1};
  b.add(make_box({0, 1, 0}, {1, 2, 1}), 0.0, InteriorKind::volume, 1.0);
  return b.scene;
}

TEST(EffectLosses, ListEveryEffectOnceWithItsCount) {
  const std::vector<EffectTreatment> e = effect_treatments(effects_scene(), "shadowmap");
  ASSERT_EQ(e.size(), 5u);
  EXPECT_EQ(e[0].effect, "translucent casters (0 < alpha < 1)");
  EXPECT_EQ(e[0].objects, 2);
  EXPECT_EQ(e[1].effect, "transmissive (glass) caster");
  EXPECT_EQ(e[2].effect, "constant media");
  EXPECT_EQ(e[2].objects, 2);
  EXPECT_EQ(e[3].effect, "volume");
  EXPECT_EQ(e[4].effect, "tinted media or coloured glass objects");  // blue medium, red glass
  EXPECT_EQ(e[4].objects, 2);
}

TEST(EffectLosses, ShadowMapsDropMediaAndMakeTranslucentCastersOpaque) {
  const std::string text = explain_effects(effects_scene(), "shadowmap");
  EXPECT_TRUE(has(text, "effects in the scene and what shadowmap shadows do with them:\n")) << text;
  EXPECT_TRUE(has(text,
                  "  2 translucent casters (0 < alpha < 1): opaque: one depth layer, so "
                  "any alpha > 0 casts a full shadow\n"))
      << text;
  EXPECT_TRUE(has(text, "  2 constant media: dropped: only its boundary casts")) << text;
  EXPECT_TRUE(has(text, "  1 volume: dropped")) << text;
  EXPECT_TRUE(
      has(text, "2 tinted media or coloured glass objects: colour dropped: shadows are grey"))
      << text;
}

TEST(EffectLosses, DeepShadowMapsKeepMediaButNotColour) {
  const std::string dsm = explain_effects(effects_scene(), "dsm");
  EXPECT_TRUE(has(dsm, "  2 constant media: kept: its extinction along each chord")) << dsm;
  EXPECT_TRUE(has(dsm, "  1 volume: approximated: sampled at the volume step")) << dsm;
  EXPECT_TRUE(has(dsm, "colour dropped: shadows are grey (the mean of the three extinctions"))
      << dsm;
  const std::string slices = explain_effects(effects_scene(), "transmittance-slicemap");
  EXPECT_TRUE(has(slices, "2 constant media: dropped: only surfaces are voxelized")) << slices;
  EXPECT_TRUE(has(explain_effects(effects_scene(), "auto"), "the planner runs dsm"));
  EXPECT_TRUE(has(explain_effects(effects_scene(), "reference"), "1 volume: kept (adaptive"));
  EXPECT_TRUE(
      has(explain_effects(effects_scene(), "some-new-method"), "not described for this method"));
}

TEST(EffectLosses, OpaqueScenesLoseNothing) {
  test::SceneBuilder b;
  b.add(make_box({-1, -1, -1}, {1, 1, 1}));
  EXPECT_TRUE(effect_treatments(b.scene, "shadowmap").empty());
  EXPECT_EQ(explain_effects(b.scene, "shadowmap"),
            "effects: every shadow caster is opaque; shadowmap drops nothing\n");
}

}  // namespace
}  // namespace dv
