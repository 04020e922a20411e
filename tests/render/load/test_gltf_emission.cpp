// glTF emission and the exposure of photometric lights: emissiveFactor (times
// KHR_materials_emissive_strength) is drawn in the camera pass as added light where the surface
// covers, times its emissiveTexture's texels where it has one; a file whose
// lights are all its own photometric ones is seen at log2(683 / pi) EV, the exposure that shows
// them as glTF viewers do, with its ambient level and emission stored on that scale.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/log.h"
#include "render/frame/reference_render.h"
#include "render/io/image.h"
#include "render/load/gltf_import.h"
#include "render/load/scene_loader.h"
#include "strategies/shadow/shadow_method.h"
#include "tests/render/load/gltf_builder.h"

namespace dv {
namespace {

using test::GltfBuilder;
using test::json;
using test::ScratchDir;

constexpr double kPi = 3.14159265358979323846;

// The unit quad (0,0,0)-(1,1,0) facing +z with `material` (and TEXCOORD_0 with `texcoords`); a
// camera 2 units in front of it.
GltfBuilder quad(const json& material, bool texcoords = false) {
  GltfBuilder b;
  add_quad_node(b, material, texcoords);
  b.doc["cameras"] =
      json::array({{{"type", "perspective"},
                    {"perspective", {{"yfov", 0.6}, {"aspectRatio", 1.0}, {"znear", 0.1}}}}});
  b.add_node({{"camera", 0}, {"translation", {0.5, 0.5, 2.0}}});
  return b;
}

// A point light of `candela` at (0.5, 0.5, 1), one unit in front of the quad's centre.
void add_point_light(GltfBuilder& b, double candela) {
  b.use_extension("KHR_lights_punctual");
  const int light = b.add_light({{"type", "point"}, {"intensity", candela}});
  b.add_node({{"translation", {0.5, 0.5, 1.0}},
              {"extensions", {{"KHR_lights_punctual", {{"light", light}}}}}});
}

json grey(const json& extra = json::object()) {
  json m = {{"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.5, 0.5, 1.0}}}}};
  m.update(extra);
  return m;
}

Image render(Scene scene) {
  scene.camera.width = scene.camera.height = 16;
  const SceneData data(scene, Memory::host);
  auto none = shadow_registry().create("none");
  return render_reference(Backend::cpu, data, scene.camera, *none, dvec3(0.0)).image;
}

TEST(GltfEmission, EmissiveFactorIsAddedWhereTheSurfaceCovers) {
  ScratchDir dir;
  const Scene dark = load_gltf_scene(quad(grey()).write_gltf(dir.file("dark.gltf")));
  const Scene glowing = load_gltf_scene(
      quad(grey({{"emissiveFactor", {0.5, 0.25, 0.0}}})).write_gltf(dir.file("glow.gltf")));
  EXPECT_EQ(glowing.objects[0].material.emission, dvec3(0.5, 0.25, 0.0));  // staged: EV 0
  const Image a = render(dark), b = render(glowing);
  const dvec3 centre = b.at(8, 8) - a.at(8, 8);
  EXPECT_NEAR(centre.x, 0.5, 1e-6);
  EXPECT_NEAR(centre.y, 0.25, 1e-6);
  EXPECT_NEAR(centre.z, 0.0, 1e-6);
  EXPECT_EQ(b.at(0, 0), a.at(0, 0));  // the background: no surface, no emission
}

TEST(GltfEmission, EmissiveStrengthScalesTheFactorAndBlendCoverageWeighsIt) {
  ScratchDir dir;
  GltfBuilder b = quad(
      grey({{"emissiveFactor", {1.0, 0.5, 0.0}},
            {"alphaMode", "BLEND"},
            {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4.0}}}}}}));
  b.doc["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"][3] = 0.5;
  b.use_extension("KHR_materials_emissive_strength");
  const Scene scene = load_gltf_scene(b.write_gltf(dir.file("strong.gltf")));
  EXPECT_EQ(scene.objects[0].material.emission, dvec3(4.0, 2.0, 0.0));
  Scene without = scene;
  without.objects[0].material.emission = dvec3(0.0);
  const dvec3 added = render(scene).at(8, 8) - render(without).at(8, 8);
  EXPECT_NEAR(added.x, 0.5 * 4.0, 1e-6);  // half covered
  EXPECT_NEAR(added.y, 0.5 * 2.0, 1e-6);
}

// The unit quad of quad() with TEXCOORD_0 (u, v) = (x, 1 - y) and an emissive texture: a 2 x 1
// PNG (left texel `left`, right `right`, 8-bit sRGB) through a NEAREST, CLAMP sampler.
GltfBuilder emissive_quad(ScratchDir& dir, const json& material,
                          const std::vector<unsigned char>& rgb) {
  GltfBuilder b = quad(material, true);
  write_png_bytes(dir.file("glow.png"), 2, 1, rgb);
  b.doc["images"] = json::array({{{"uri", "glow.png"}}});
  b.doc["samplers"] = json::array({{{"magFilter", 9728}, {"wrapS", 33071}, {"wrapT", 33071}}});
  b.doc["textures"] = json::array({{{"source", 0}, {"sampler", 0}}});
  return b;
}

double srgb_linear(unsigned char byte) {
  const double c = byte / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

// An emissiveTexture multiplies the factor by its texel's linear RGB where the surface covers:
// the left and right halves of the quad glow in their texels' colours, without a warning.
TEST(GltfEmission, EmissiveTextureDrawsItsTexels) {
  ScratchDir dir;
  const std::vector<unsigned char> rgb = {255, 128, 0, 0, 64, 255};  // left, right texel
  GltfBuilder b = emissive_quad(
      dir, grey({{"emissiveFactor", {1.0, 0.5, 1.0}}, {"emissiveTexture", {{"index", 0}}}}), rgb);
  const int before = warning_count();
  const Scene scene = load_gltf_scene(b.write_gltf(dir.file("glow.gltf")));
  EXPECT_EQ(warning_count(), before);
  const Material& m = scene.objects[0].material;
  EXPECT_EQ(m.emission, dvec3(1.0, 0.5, 1.0));
  ASSERT_EQ(m.emissive_texture, 0);
  EXPECT_EQ(m.base_texture, -1);
  Scene dark = scene;
  dark.objects[0].material.emission = dvec3(0.0);
  const Image lit = render(scene), unlit = render(dark);
  // Pixel column 4 sees x of about 0.23 (the left texel), column 11 about 0.77 (the right).
  for (const auto& [column, texel] : {std::pair{4, 0}, std::pair{11, 1}}) {
    const dvec3 added = lit.at(column, 8) - unlit.at(column, 8);
    const dvec3 expected = dvec3(srgb_linear(rgb[3 * texel]), srgb_linear(rgb[3 * texel + 1]),
                                 srgb_linear(rgb[3 * texel + 2])) *
                           m.emission;
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(added[c], expected[c], 1e-6) << "column " << column << " channel " << c;
  }
  EXPECT_EQ(lit.at(0, 0), unlit.at(0, 0));  // the background: no surface, no emission
}

// Its KHR_texture_transform is its own: an offset of half the texture shows the right texel on
// the left half too (CLAMP beyond it); an unusable image drops the emission, naming the image.
TEST(GltfEmission, EmissiveTextureTransformAndMissingImage) {
  ScratchDir dir;
  const std::vector<unsigned char> rgb = {255, 0, 0, 0, 0, 255};
  GltfBuilder b = emissive_quad(
      dir,
      grey({{"emissiveFactor", {1.0, 1.0, 1.0}},
            {"emissiveTexture",
             {{"index", 0},
              {"extensions", {{"KHR_texture_transform", {{"offset", {0.5, 0.0}}}}}}}}}),
      rgb);
  b.use_extension("KHR_texture_transform");
  const Scene shifted = load_gltf_scene(b.write_gltf(dir.file("shifted.gltf")));
  Scene dark = shifted;
  dark.objects[0].material.emission = dvec3(0.0);
  const dvec3 left = render(shifted).at(4, 8) - render(dark).at(4, 8);
  EXPECT_NEAR(left.x, 0.0, 1e-6);
  EXPECT_NEAR(left.z, 1.0, 1e-6);

  b.doc["images"][0]["uri"] = "gone.png";
  const int before = warning_count();
  testing::internal::CaptureStderr();
  const Scene missing = load_gltf_scene(b.write_gltf(dir.file("missing.gltf")));
  const std::string log = testing::internal::GetCapturedStderr();
  EXPECT_GE(warning_count() - before, 1) << log;
  EXPECT_NE(log.find("gone.png"), std::string::npos) << log;
  EXPECT_EQ(missing.objects[0].material.emission, dvec3(0.0));
  EXPECT_EQ(missing.objects[0].material.emissive_texture, -1);
}

// A file lit by its own photometric lights is seen at log2(683 / pi) EV: there a white
// Lambertian surface under E lux shows E / pi, as in glTF viewers, and ambient and emission keep
// the look they have in a staged scene at 0 EV.
TEST(GltfEmission, PhotometricLightsSetTheExposureAndItsScale) {
  ScratchDir dir;
  GltfBuilder lit = quad(grey({{"emissiveFactor", {0.2, 0.0, 0.0}}}));
  add_point_light(lit, kPi);  // pi lux at the quad's centre: it shows diffuse * colour there
  const Scene scene = load_gltf_scene(lit.write_gltf(dir.file("lit.gltf")));
  const double ev = default_exposure_ev(scene);
  EXPECT_NEAR(ev, std::log2(683.0 / kPi), 1e-12);
  EXPECT_NEAR(ev, 7.764, 1e-3);
  const Material& m = scene.objects[0].material;
  EXPECT_NEAR(m.emission.x * std::exp2(ev), 0.2, 1e-12);
  EXPECT_NEAR(m.ambient * std::exp2(ev), 0.1, 1e-12);
  // At that exposure the centre shows ambient + diffuse * colour * E (E = pi lux at 1 unit,
  // facing the light) + the highlight (specular 0.04 of roughness 1, mirrored at the camera) +
  // emission, as the staged scene's units would: 0.1 * 0.5 + 0.8 * 0.5 + 0.04, 0.2 more in red.
  const dvec3 shown = render(scene).at(8, 8) * std::exp2(ev);
  EXPECT_NEAR(shown.y, 0.05 + 0.4 + 0.04, 0.005);
  EXPECT_NEAR(shown.x - shown.y, 0.2, 1e-4);
  // Staged lights (no light in the file) keep 0 EV and the display quantities as they are.
  const Scene staged = load_gltf_scene(quad(grey()).write_gltf(dir.file("staged.gltf")));
  EXPECT_EQ(default_exposure_ev(staged), 0.0);
  EXPECT_EQ(staged.objects[0].material.ambient, 0.1);
}

// A JSON scene that imports the file but brings its own lights is seen at 0 EV: the imported
// ambient and emission are put back on that scale.
TEST(GltfEmission, JsonSceneWithItsOwnLightsPutsImportedDisplayQuantitiesBack) {
  ScratchDir dir;
  GltfBuilder lit = quad(grey({{"emissiveFactor", {0.2, 0.0, 0.0}}}));
  add_point_light(lit, 10.0);
  lit.write_gltf(dir.file("lit.gltf"));
  test::write_text(dir.file("own.json"), R"({"import": {"file": "lit.gltf", "lights": false},
      "lights": [{"type": "directional", "direction": [0, 0, -1], "intensity": 1}]})");
  const Scene own = load_scene(dir.file("own.json"));
  EXPECT_EQ(default_exposure_ev(own), 0.0);
  EXPECT_NEAR(own.objects[0].material.emission.x, 0.2, 1e-12);
  EXPECT_NEAR(own.objects[0].material.ambient, 0.1, 1e-12);
  test::write_text(dir.file("kept.json"), R"({"import": {"file": "lit.gltf", "light_scale": 2}})");
  const Scene kept = load_scene(dir.file("kept.json"));
  const double ev = default_exposure_ev(kept);
  EXPECT_NEAR(ev, std::log2(683.0 / kPi), 1e-12);
  EXPECT_NEAR(kept.objects[0].material.emission.x * std::exp2(ev), 0.2, 1e-12);
}

}  // namespace
}  // namespace dv
