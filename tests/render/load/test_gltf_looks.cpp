// glTF scenes as a user would see them: transmissive glass shows Phong highlights, a Fresnel
// reflection, and tints what is behind it by its base colour, and casts the same tinted,
// partial shadow (engine/scene/surface_transmittance.h); a tinted KHR_materials_volume medium
// tints the camera image and the shadows per channel, its surfaces adding only Fresnel; and JSON
// scenes that import a glTF keep, scale or replace its lights and get default lights only when
// they end up with none.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "engine/oracle/transmittance.h"
#include "engine/raster/camera_rays.h"
#include "engine/scene/surface_transmittance.h"
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
  // The file's sun is photometric, so its ambient level is stored for log2(683 / pi) EV
  // (gltf_import.h, "Exposure"); these tests look at the linear image, at 0 EV.
  Material& box = scene.objects[1].material;
  EXPECT_NEAR(box.ambient * std::exp2(photometric_exposure_ev()), 0.1, 1e-15);
  box.ambient = 0.1;
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
  // Off the highlight: the wall through two crossings of the glass (the pixel's ray enters by
  // the front face and leaves by the back one), each passing (1 - F) times the colour
  // (1, .25, .25) and reflecting F of the ambient 0.1 (F: Schlick, ior 1.5).
  const dvec3 tinted = with.at(22, 14), wall = behind.at(22, 14);
  EXPECT_NEAR(wall.y, 1.0, 1e-12);
  const dvec3 ray = camera_ray_direction(make_camera_view(scene.camera), 22, 14);
  const double f = fresnel_schlick(1.5, ray.z), ambient = 0.1;
  const dvec3 crossing = (1.0 - f) * dvec3(1.0, 0.25, 0.25);
  const dvec3 expected = wall * crossing * crossing + f * ambient + crossing * f * ambient;
  EXPECT_NEAR(tinted.x, expected.x, 5e-3);  // a residual of 0.003 beyond these terms remains
  EXPECT_NEAR(tinted.y, expected.y, 5e-3);
  EXPECT_NEAR(tinted.z, expected.z, 5e-3);
  EXPECT_GT(tinted.x, 10.0 * tinted.y);  // tinted twice by (1, .25, .25)
  // Facing the light: a Phong highlight (specular 0.24 of irradiance 1 at the front face).
  const dvec3 centre = with.at(32, 24);
  EXPECT_GT(centre.y - behind.at(32, 24).y / 16.0, 0.2);
  // Shadows follow the same rule: two crossings at normal incidence (F = 0.04), tinted.
  const SceneData data(scene, Memory::host);
  const OracleResult shadow =
      exact_transmittance(data.view(), data.view().lights[0], {0.0, 0.0, -2.9});
  EXPECT_NEAR(shadow.rgb.x, 0.96 * 0.96, 1e-12);
  EXPECT_NEAR(shadow.rgb.y, 0.96 * 0.96 / 16.0, 1e-12);
  EXPECT_NEAR(shadow.transmittance, luminance(shadow.rgb), 1e-15);
}

TEST(GltfLooks, TintedMediumTintsTheCameraImageAndTheShadows) {
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
  // The surfaces add only Fresnel (the medium colours): (1 - F) per crossing, F of the
  // ambient 0.1 reflected at each.
  const double f = fresnel_schlick(1.5, dir_centre.z), ambient = 0.1;
  const dvec3 inside(1.0, std::exp(-std::log(4.0) * chord), std::exp(-std::log(4.0) * chord));
  const dvec3 expected =
      wall * (1.0 - f) * (1.0 - f) * inside + f * ambient + (1.0 - f) * inside * f * ambient;
  EXPECT_NEAR(seen.x, expected.x, 1e-6);  // red passes
  EXPECT_NEAR(seen.y, expected.y, 1e-6);
  EXPECT_NEAR(seen.z, expected.z, 1e-6);
  EXPECT_GT(seen.x, 4.0 * seen.y);  // red-tinted
  // Shadows: per channel, two crossings of the top and bottom at normal incidence and 2 units
  // of medium.
  const SceneData data(scene, Memory::host);
  const OracleResult t = exact_transmittance(data.view(), data.view().lights[0], {0.0, -1.5, 0.0});
  EXPECT_NEAR(t.rgb.x, 0.96 * 0.96, 1e-9);
  EXPECT_NEAR(t.rgb.y, 0.96 * 0.96 * std::exp(-2.0 * std::log(4.0)), 1e-9);
  EXPECT_NEAR(t.rgb.z, t.rgb.y, 1e-12);
  EXPECT_GT(t.rgb.x, 10.0 * t.rgb.y);  // a red shadow, not a grey one
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
