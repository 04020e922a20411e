// glTF scenes as a user would see them: transmissive glass shows Phong highlights and tints
// what is behind it by its base colour while casting what its alpha says (nothing at
// transmission 1); a tinted KHR_materials_volume medium tints the camera image per channel
// while shadows stay scalar; and JSON scenes that import a glTF keep, scale or replace its
// lights and get default lights only when they end up with none.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "engine/oracle/transmittance.h"
#include "engine/raster/camera_rays.h"
#include "render/frame/reference_render.h"
#include "render/load/gltf_import.h"
#include "render/load/scene_loader.h"
#include "strategies/shadow/shadow_method.h"
#include "tests/render/load/gltf_builder.h"

namespace dv {
namespace {

using test::GltfBuilder;
using test::json;
using test::ScratchDir;

constexpr double kHalf = 0.70710678118654752440;

json light_ext(int light) {
  return {{"KHR_lights_punctual", {{"light", light}}}};
}

// A white wall (node 0) at z = -3 facing a camera at (0, 0, 6) looking along -z, a unit box
// with `material` at the origin and a directional light of 683 lux (1 W/m^2) shining along
// -z or, with `from_above`, straight down.
Scene box_before_wall(const ScratchDir& dir, const json& material, bool from_above) {
  GltfBuilder b;
  b.use_extension("KHR_lights_punctual");
  b.use_extension("KHR_materials_transmission");
  b.use_extension("KHR_materials_volume");
  b.add_node(
      {{"mesh", test::add_box_mesh(b)}, {"translation", {0, 0, -3}}, {"scale", {3, 3, 0.1}}});
  b.add_node({{"mesh", test::add_box_mesh(b, {{"material", b.add_material(material)}})}});
  b.doc["cameras"] =
      json::array({{{"type", "perspective"},
                    {"perspective", {{"yfov", 0.5}, {"aspectRatio", 4.0 / 3.0}, {"znear", 0.1}}}}});
  b.add_node({{"camera", 0}, {"translation", {0, 0, 6}}});
  const int sun = b.add_light({{"type", "directional"}, {"intensity", 683.0}});
  json sun_node = {{"extensions", light_ext(sun)}};
  if (from_above) sun_node["rotation"] = {-kHalf, 0, 0, kHalf};  // -Z turned to -Y
  b.add_node(sun_node);
  Scene scene = load_gltf_scene(b.write_gltf(dir.file("box.gltf")));
  Material& wall = scene.objects[0].material;  // shows its colour whatever the lighting
  wall.ambient = 1.0, wall.diffuse = 0.0, wall.specular = 0.0;
  scene.camera.width = 64;
  scene.camera.height = 48;
  return scene;
}

Image render(const Scene& scene) {
  const SceneData data(scene, Memory::host);
  auto none = shadow_registry().create("none");
  return render_reference(Backend::cpu, data, scene.camera, *none, dvec3(0.0)).image;
}

// The same scene with the box invisible: what lies behind it.
Image render_without_box(Scene scene) {
  scene.objects[1].material.alpha = 0.0;
  scene.objects[1].material.transmission = 0.0;
  scene.objects[1].interior = Interior{};
  return render(scene);
}

TEST(GltfLooks, TransmissiveGlassShowsHighlightsAndTintsWhatIsBehind) {
  ScratchDir dir;
  const json glass = {
      {"pbrMetallicRoughness",
       {{"baseColorFactor", {1.0, 0.25, 0.25, 1.0}}, {"roughnessFactor", 0.0}}},
      {"extensions", {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}}}}};
  const Scene scene = box_before_wall(dir, glass, false);
  const Image with = render(scene), behind = render_without_box(scene);
  // Off the highlight: the wall through two crossings of the glass, tinted by (1, .25, .25)^2.
  const dvec3 tinted = with.at(16, 12), wall = behind.at(16, 12);
  EXPECT_NEAR(wall.y, 1.0, 1e-12);
  EXPECT_NEAR(tinted.x, wall.x, 1e-3);
  EXPECT_NEAR(tinted.y, wall.y / 16.0, 1e-3);
  EXPECT_NEAR(tinted.z, wall.z / 16.0, 1e-3);
  // Facing the light: a Phong highlight (specular 0.24 of irradiance 1 at the front face).
  const dvec3 centre = with.at(32, 24);
  EXPECT_GT(centre.y - behind.at(32, 24).y / 16.0, 0.2);
  // Shadows keep the physical mapping: alpha = 1 - transmission = 0 casts nothing.
  const SceneData data(scene, Memory::host);
  EXPECT_EQ(exact_transmittance(data.view(), data.view().lights[0], {0.0, 0.0, -2.9}).transmittance,
            1.0);
}

TEST(GltfLooks, TintedMediumTintsTheCameraImageButShadowsStayScalar) {
  ScratchDir dir;
  // attenuationColor (1, .25, .25) at distance 1: sigma = (0, ln 4, ln 4) per unit.
  const json medium = {{"extensions",
                        {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}},
                         {"KHR_materials_volume",
                          {{"thicknessFactor", 1.0},
                           {"attenuationColor", {1.0, 0.25, 0.25}},
                           {"attenuationDistance", 1.0}}}}}};
  const Scene scene = box_before_wall(dir, medium, true);
  const Image with = render(scene), behind = render_without_box(scene);
  const dvec3 dir_centre = camera_ray_direction(make_camera_view(scene.camera), 32, 24);
  const double chord = 2.0 / std::abs(dir_centre.z);  // through the box from z = 1 to z = -1
  const dvec3 seen = with.at(32, 24), wall = behind.at(32, 24);
  EXPECT_NEAR(seen.x, wall.x, 1e-6);  // red passes
  EXPECT_NEAR(seen.y, wall.y * std::exp(-std::log(4.0) * chord), 1e-6);
  EXPECT_NEAR(seen.z, wall.z * std::exp(-std::log(4.0) * chord), 1e-6);
  EXPECT_GT(seen.x, 4.0 * seen.y);  // red-tinted
  // Shadows: the oracle's scalar transmittance with the mean extinction 2 ln 4 / 3.
  const SceneData data(scene, Memory::host);
  const double t =
      exact_transmittance(data.view(), data.view().lights[0], {0.0, -1.5, 0.0}).transmittance;
  EXPECT_NEAR(t, std::exp(-2.0 * (2.0 * std::log(4.0) / 3.0)), 1e-9);
}

// A glTF file with one box and, if `lit`, a 683 cd point light above it.
std::string write_model(const ScratchDir& dir, bool lit) {
  GltfBuilder b;
  b.add_node({{"mesh", test::add_box_mesh(b)}});
  if (lit) {
    b.use_extension("KHR_lights_punctual");
    b.add_node({{"translation", {0, 4, 0}},
                {"extensions", light_ext(b.add_light({{"type", "point"}, {"intensity", 683}}))}});
  }
  return b.write_gltf(dir.file(lit ? "lit.gltf" : "bare.gltf"));
}

Scene load_json(const ScratchDir& dir, const std::string& text) {
  test::write_text(dir.file("scene.json"), text);
  return load_scene(dir.file("scene.json"));
}

TEST(GltfJsonImport, AddedLightsReplaceTheDefaultOnes) {
  ScratchDir dir;
  write_model(dir, false);
  const Scene own = load_json(
      dir, R"({"import": "bare.gltf", "lights": [{"type": "omni", "position": [0, 5, 0]}]})");
  ASSERT_EQ(own.lights.size(), 1u);  // no extra default light
  EXPECT_EQ(own.lights[0].type, LightType::omni);
  const Scene none = load_json(dir, R"({"import": "bare.gltf"})");
  EXPECT_EQ(none.lights.size(), 2u);  // the default key and fill
}

TEST(GltfJsonImport, ImportedLightsCanBeScaledOrReplaced) {
  ScratchDir dir;
  write_model(dir, true);
  const Scene kept = load_json(
      dir, R"({"import": "lit.gltf", "lights": [{"type": "omni", "position": [0, 5, 0]}]})");
  ASSERT_EQ(kept.lights.size(), 2u);
  EXPECT_DOUBLE_EQ(kept.lights[0].intensity, 1.0);  // 683 cd
  const Scene scaled = load_json(dir, R"({"import": {"file": "lit.gltf", "light_scale": 0.25}})");
  ASSERT_EQ(scaled.lights.size(), 1u);
  EXPECT_DOUBLE_EQ(scaled.lights[0].intensity, 0.25);
  EXPECT_DOUBLE_EQ(scaled.lights[0].source_intensity, 683.0 * 0.25);
  const Scene replaced = load_json(dir, R"({"import": {"file": "lit.gltf", "lights": false},
      "lights": [{"type": "directional", "direction": [0, -1, 0], "intensity": 3}]})");
  ASSERT_EQ(replaced.lights.size(), 1u);
  EXPECT_EQ(replaced.lights[0].type, LightType::directional);
  EXPECT_DOUBLE_EQ(replaced.lights[0].intensity, 3.0);
  EXPECT_THROW(load_json(dir, R"({"import": {"file": "lit.gltf", "light_scale": -1}})"),
               InputError);
  EXPECT_THROW(load_json(dir, R"({"import": {"file": "lit.gltf", "lamps": 1}})"), InputError);
}

TEST(GltfJsonImport, GroundTransmissionAndTintedSigmaKeys) {
  ScratchDir dir;
  write_model(dir, false);
  const Scene scene = load_json(dir, R"({"import": "bare.gltf", "ground": true,
      "objects": [{"mesh": {"generator": "icosphere", "radius": 0.5, "subdivisions": 1},
                   "material": {"alpha": 0.2, "transmission": 0.7, "color": [1, 0, 0]},
                   "interior": {"type": "constant", "sigma": [0, 3, 3]}}]})");
  ASSERT_EQ(scene.objects.size(), 3u);
  EXPECT_EQ(scene.objects[2].name, "ground");
  EXPECT_DOUBLE_EQ(scene.objects[1].material.transmission, 0.7);
  EXPECT_DOUBLE_EQ(scene.objects[1].interior.sigma, 2.0);  // the mean, for shadows
  EXPECT_DOUBLE_EQ(scene.objects[1].interior.sigma_tint.y, 1.5);
  EXPECT_THROW(load_json(dir, R"({"import": "bare.gltf", "objects": [{"mesh": {"generator":
      "icosphere"}, "material": {"alpha": 0.5, "transmission": 0.7}}]})"),
               InputError);
}

}  // namespace
}  // namespace dv
