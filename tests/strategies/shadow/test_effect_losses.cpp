// What `--explain` says each shadow method drops of a scene's effects (effect_losses.h): the
// effects are found from the materials, textures and interiors, each named once with its count,
// and the text for a method is its entry of the table, as the merged glass, texture and media
// code does it: e.g. shadowmap thresholds at 0.5 and carries glass in its glass layer.
#include <gtest/gtest.h>

#include <string>

#include "experiments/source_paths.h"
#include "render/load/gltf_import.h"
#include "render/load/mesh_generators.h"
#include "strategies/shadow/effect_losses.h"
#include "tests/support/scene_builder.h"

namespace dv {
namespace {

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

// The committed cut-out stand-in: a floor, a MASK quad and a BLEND quad (factor alpha 0.4).
Scene alpha_textured_scene() {
  return load_gltf_scene(test::source_dir() + "/tests/data/textured/alpha_mask_quad.gltf");
}

// A floor, a red glass slab (transmission 1, ior 1.5) and an opaque block.
Scene red_glass_scene() {
  return load_gltf_scene(test::source_dir() + "/experiments/assets/gltf/red-glass-slab.gltf");
}

std::string header(const std::string& method) {
  return "effects in the scene and what " + method + " shadows do with them:\n";
}

// Each row's words per method, as --explain prints them after the count.
const std::string kTranslucentShadowMap =
    "thresholded: one depth layer, so alpha >= 0.5 casts a full shadow and alpha < 0.5 none";
const std::string kTranslucentDsm =
    "kept: its alpha per crossing, in visibility functions compressed to within eps";
const std::string kTranslucentSlices =
    "approximated: voxelized into the light's slices with one alpha, the mean over the "
    "translucent casters when theirs differ";
const std::string kTexturedShadowMap =
    "MASK cut per shadow-map texel; BLEND thresholded per texel: a full shadow where the "
    "texel's alpha times the factor's reaches 0.5, none below";
const std::string kTexturedDsm =
    "kept: MASK cut and BLEND alpha per crossing of each texel's ray, in visibility functions "
    "compressed to within eps";
const std::string kTexturedSlices =
    "MASK cut per texel by the opaque depth map; BLEND approximated: voxelized with the "
    "factor's alpha everywhere, since the grid holds no texture (with a factor's alpha of 1 "
    "only its fully opaque texels cast, through the opaque depth map)";
const std::string kTexturedReference = "kept (exact: the texel's coverage at every crossing)";
const std::string kTexturedAuto =
    "MASK on an opaque object cut per texel by the shadowmap the planner runs where every "
    "caster is opaque (else by dsm); BLEND kept as dsm keeps it: the planner runs dsm for "
    "every light that reaches it";
const std::string kGlassShadowMap =
    "approximated: a glass layer, one per texel: the crossing rule (Fresnel at the texel ray's "
    "angle, tint) multiplied over the texel's glass crossings, applied beyond the nearest, so a "
    "receiver between two of them gets both (no refraction, no caustics)";
const std::string kGlassDsm =
    "kept: each crossing's opacity, 1 - the luminance of the crossing rule (Fresnel at the "
    "texel ray's angle), in visibility functions compressed to within eps; its colour by the "
    "colour side channel (no refraction, no caustics)";
const std::string kGlassSlices =
    "approximated as shadowmap does: the opaque depth map's glass layer, one per texel (no "
    "refraction, no caustics)";
const std::string kGlassReference =
    "kept (exact: the crossing rule with Fresnel at every crossing; thin-walled, no "
    "refraction, no caustics)";
const std::string kAsDsm =
    "kept as dsm keeps it: the planner runs dsm for every light that reaches it";
const std::string kMediumShadowMap =
    "thresholded at its boundary: a full shadow where the medium's opacity across the object's "
    "thinnest extent d, 1 - exp(-sigma d), or its surface alpha reaches 0.5, else none (inside "
    "glass: the glass layer's Fresnel alone)";
const std::string kMediumDsm =
    "kept: its extinction along each chord, in the compressed visibility functions";
const std::string kMediumSlices =
    "approximated: its boundary is voxelized, each crossing 1 - exp(-sigma d / 2) with d the "
    "object's thinnest extent, under the translucent casters' one alpha (their mean when they "
    "differ)";
const std::string kVolumeShadowMap =
    "thresholded at its boundary: a full shadow where 1 - exp(-sigma_max d), sigma_max its "
    "transfer function's largest extinction and d the object's thinnest extent, reaches 0.5, "
    "else none";
const std::string kVolumeDsm =
    "approximated: sampled at the volume step when the maps are generated";
const std::string kVolumeSlices =
    "approximated: its boundary is voxelized, each crossing 1 - exp(-sigma_max d / 2) with "
    "sigma_max its transfer function's largest extinction and d the object's thinnest extent, "
    "under the translucent casters' one alpha (their mean when they differ)";
const std::string kTintShadowMap =
    "coloured glass kept in the glass layer (one colour filter per texel); a tinted medium's "
    "colour dropped: its boundary casts grey";
const std::string kTintDsm =
    "kept by the colour side channel: exact for one tint per texel at every depth; where "
    "differently tinted casters share a texel, the far end's mix holds at every depth";
const std::string kTintSlices =
    "coloured glass kept in the opaque depth map's glass layer (one colour filter per texel); a "
    "tinted medium's colour dropped: its boundary is voxelized grey";
const std::string kTintReference = "kept (exact, per colour channel)";
const std::string kTintAuto =
    "kept as dsm keeps it (the colour side channel): the planner runs dsm for every light that "
    "reaches it";

TEST(EffectLosses, ListEveryEffectOnceWithItsCount) {
  const std::vector<EffectTreatment> e = effect_treatments(effects_scene(), "shadowmap");
  ASSERT_EQ(e.size(), 5u);
  EXPECT_EQ(e[0].effect, "translucent casters (0 < alpha < 1)");
  EXPECT_EQ(e[0].objects, 2);
  EXPECT_EQ(e[1].effect, "transmissive (glass) caster");
  EXPECT_EQ(e[1].objects, 1);
  EXPECT_EQ(e[2].effect, "constant media");
  EXPECT_EQ(e[2].objects, 2);
  EXPECT_EQ(e[3].effect, "volume");
  EXPECT_EQ(e[3].objects, 1);
  EXPECT_EQ(e[4].effect, "tinted media or coloured glass objects");  // blue medium, red glass
  EXPECT_EQ(e[4].objects, 2);
}

// Depth maps threshold translucent casters and media boundaries at 0.5 and carry glass, in
// colour, in their glass layer; a tinted medium's boundary casts grey.
TEST(EffectLosses, ShadowMapsThresholdAtHalfAndCarryGlassInTheGlassLayer) {
  EXPECT_EQ(explain_effects(effects_scene(), "shadowmap"),
            header("shadowmap") + "  2 translucent casters (0 < alpha < 1): " +
                kTranslucentShadowMap + "\n  1 transmissive (glass) caster: " + kGlassShadowMap +
                "\n  2 constant media: " + kMediumShadowMap + "\n  1 volume: " + kVolumeShadowMap +
                "\n  2 tinted media or coloured glass objects: " + kTintShadowMap + "\n");
  EXPECT_EQ(explain_effects(effects_scene(), "transmittance-slicemap"),
            header("transmittance-slicemap") + "  2 translucent casters (0 < alpha < 1): " +
                kTranslucentSlices + "\n  1 transmissive (glass) caster: " + kGlassSlices +
                "\n  2 constant media: " + kMediumSlices + "\n  1 volume: " + kVolumeSlices +
                "\n  2 tinted media or coloured glass objects: " + kTintSlices + "\n");
}

// Deep shadow maps keep media and carry colour by their side channel; the planner runs them.
TEST(EffectLosses, DeepShadowMapsKeepMediaAndColour) {
  EXPECT_EQ(explain_effects(effects_scene(), "dsm"),
            header("dsm") + "  2 translucent casters (0 < alpha < 1): " + kTranslucentDsm +
                "\n  1 transmissive (glass) caster: " + kGlassDsm +
                "\n  2 constant media: " + kMediumDsm + "\n  1 volume: " + kVolumeDsm +
                "\n  2 tinted media or coloured glass objects: " + kTintDsm + "\n");
  EXPECT_EQ(explain_effects(effects_scene(), "auto"),
            header("auto") + "  2 translucent casters (0 < alpha < 1): " + kAsDsm +
                "\n  1 transmissive (glass) caster: " + kAsDsm + "\n  2 constant media: " + kAsDsm +
                "\n  1 volume: approximated as dsm does: the planner runs dsm with volume "
                "sampling for every light that reaches it\n"
                "  2 tinted media or coloured glass objects: " +
                kTintAuto + "\n");
  EXPECT_EQ(explain_effects(effects_scene(), "reference"),
            header("reference") + "  2 translucent casters (0 < alpha < 1): kept (exact)\n" +
                "  1 transmissive (glass) caster: " + kGlassReference +
                "\n  2 constant media: kept (exact chord lengths)\n"
                "  1 volume: kept (closed form per cell, exact up to rounding)\n"
                "  2 tinted media or coloured glass objects: " +
                kTintReference + "\n");
  const std::vector<EffectTreatment> none = effect_treatments(effects_scene(), "none");
  ASSERT_EQ(none.size(), 5u);
  for (const EffectTreatment& e : none) EXPECT_EQ(e.treatment, "dropped (no shadows)");
  const std::vector<EffectTreatment> unknown =
      effect_treatments(effects_scene(), "some-new-method");
  ASSERT_EQ(unknown.size(), 5u);
  for (const EffectTreatment& e : unknown) EXPECT_EQ(e.treatment, "not described for this method");
}

// The cut-out stand-in's MASK and BLEND quads are one row (their material alpha is 1, so they
// are not translucent casters): cut per texel everywhere, BLEND as each method can.
TEST(EffectLosses, AlphaTexturedCastersAreCutPerTexel) {
  const Scene scene = alpha_textured_scene();
  const std::string row = "  2 alpha-textured casters (MASK or BLEND): ";
  EXPECT_EQ(explain_effects(scene, "shadowmap"),
            header("shadowmap") + row + kTexturedShadowMap + "\n");
  EXPECT_EQ(explain_effects(scene, "dsm"), header("dsm") + row + kTexturedDsm + "\n");
  EXPECT_EQ(explain_effects(scene, "transmittance-slicemap"),
            header("transmittance-slicemap") + row + kTexturedSlices + "\n");
  EXPECT_EQ(explain_effects(scene, "reference"),
            header("reference") + row + kTexturedReference + "\n");
  EXPECT_EQ(explain_effects(scene, "auto"), header("auto") + row + kTexturedAuto + "\n");
  Scene mask_only = scene;
  std::erase_if(mask_only.objects, [](const Object& o) { return o.name == "blend"; });
  const std::vector<EffectTreatment> e = effect_treatments(mask_only, "shadowmap");
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(e[0].effect, "alpha-textured caster (MASK or BLEND)");
  EXPECT_EQ(e[0].objects, 1);
}

// The red glass slab is one glass caster that tints: every method but none keeps its colour.
TEST(EffectLosses, ColouredGlassKeepsItsColour) {
  const Scene scene = red_glass_scene();
  const std::string glass = "  1 transmissive (glass) caster: ";
  const std::string tint = "  1 tinted medium or coloured glass: ";
  EXPECT_EQ(explain_effects(scene, "shadowmap"),
            header("shadowmap") + glass + kGlassShadowMap + "\n" + tint + kTintShadowMap + "\n");
  EXPECT_EQ(explain_effects(scene, "dsm"),
            header("dsm") + glass + kGlassDsm + "\n" + tint + kTintDsm + "\n");
  EXPECT_EQ(
      explain_effects(scene, "transmittance-slicemap"),
      header("transmittance-slicemap") + glass + kGlassSlices + "\n" + tint + kTintSlices + "\n");
  EXPECT_EQ(explain_effects(scene, "reference"),
            header("reference") + glass + kGlassReference + "\n" + tint + kTintReference + "\n");
  EXPECT_EQ(explain_effects(scene, "auto"),
            header("auto") + glass + kAsDsm + "\n" + tint + kTintAuto + "\n");
}

// Clear glass and glass around a tinted medium: the glass's surfaces do not tint (white base,
// or an interior whose medium tints instead), so only the tinted medium counts.
TEST(EffectLosses, OnlyCastersThatTintCountAsColoured) {
  test::SceneBuilder b;
  Object& clear = b.add(make_box({-1, 0, 0}, {0, 1, 1}), 0.0);
  clear.material.transmission = 1.0;
  clear.material.color = {1.0, 1.0, 1.0};
  Object& shell = b.add(make_box({1, 0, 0}, {2, 1, 1}), 0.0, InteriorKind::constant, 1.0);
  shell.material.transmission = 1.0;
  shell.material.color = {1.0, 0.1, 0.1};
  const std::vector<EffectTreatment> grey = effect_treatments(b.scene, "dsm");
  ASSERT_EQ(grey.size(), 2u);
  EXPECT_EQ(grey[0].effect, "transmissive (glass) casters");
  EXPECT_EQ(grey[1].effect, "constant medium");
  shell.interior.sigma_tint = {0.3, 1.2, 1.5};
  const std::vector<EffectTreatment> tinted = effect_treatments(b.scene, "dsm");
  ASSERT_EQ(tinted.size(), 3u);
  EXPECT_EQ(tinted[2].effect, "tinted medium or coloured glass");
  EXPECT_EQ(tinted[2].objects, 1);
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
