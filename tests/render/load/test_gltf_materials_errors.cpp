// glTF import: PBR materials, transmission and volume extensions mapped to deepvox materials
// and interiors, and the InputErrors for bad files (extensions, accessors, indices, JSON, GLB).
#include <cmath>
#include <functional>
#include <initializer_list>
#include <string>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/log.h"
#include "render/load/gltf_import.h"
#include "tests/render/load/gltf_builder.h"

namespace dv {
namespace {

using test::GltfBuilder;
using test::json;
using test::ScratchDir;

// Loads a scene with one box per material, in material order.
Scene load_boxes(const ScratchDir& dir, GltfBuilder& b, const std::vector<json>& materials) {
  for (size_t i = 0; i < materials.size(); ++i) {
    int m = b.add_material(materials[i]);
    b.add_node({{"mesh", test::add_box_mesh(b, {{"material", m}})},
                {"translation", {3.0 * double(i), 0, 0}}});
  }
  return load_gltf_scene(b.write_gltf(dir.file("materials.gltf")));
}

void expect_input_error(const std::function<void()>& load,
                        std::initializer_list<std::string> needles) {
  try {
    load();
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& e) {
    std::string message = e.what();
    for (const std::string& needle : needles)
      EXPECT_NE(message.find(needle), std::string::npos)
          << "'" << needle << "' not in: " << message;
  }
}

TEST(GltfMaterials, TransmissionBlendAndMaskGiveSurfaceAlpha) {
  ScratchDir dir;
  GltfBuilder b;
  b.use_extension("KHR_materials_transmission");
  json factor = {0.2, 0.4, 0.6, 0.4};
  Scene scene = load_boxes(
      dir, b,
      {{{"extensions", {{"KHR_materials_transmission", {{"transmissionFactor", 0.25}}}}}},
       {{"alphaMode", "BLEND"}, {"pbrMetallicRoughness", {{"baseColorFactor", factor}}}},
       {{"pbrMetallicRoughness", {{"baseColorFactor", factor}}}},
       {{"alphaMode", "MASK"}, {"pbrMetallicRoughness", {{"baseColorFactor", factor}}}}});
  ASSERT_EQ(scene.objects.size(), 4u);
  EXPECT_DOUBLE_EQ(scene.objects[0].material.alpha, 0.75);
  EXPECT_EQ(scene.objects[0].interior.kind, InteriorKind::none);
  EXPECT_DOUBLE_EQ(scene.objects[1].material.alpha, 0.4);  // BLEND: the factor's alpha
  EXPECT_DOUBLE_EQ(scene.objects[1].material.color.y, 0.4);
  EXPECT_DOUBLE_EQ(scene.objects[2].material.alpha, 1.0);  // OPAQUE ignores it
  EXPECT_DOUBLE_EQ(scene.objects[3].material.alpha, 0.0);  // MASK: 0.4 < alphaCutoff 0.5
}

TEST(GltfMaterials, VolumeGivesConstantInteriorUnlessThinWalled) {
  ScratchDir dir;
  GltfBuilder b;
  json volume = {{"thicknessFactor", 1.0},
                 {"attenuationColor", {0.5, 0.5, 0.5}},
                 {"attenuationDistance", 2.0}};
  json thin = {{"attenuationColor", {0.5, 0.5, 0.5}}, {"attenuationDistance", 2.0}};
  json clear = {{"thicknessFactor", 0.5}};
  auto with = [](const json& v) {
    return json{{"extensions",
                 {{"KHR_materials_volume", v},
                  {"KHR_materials_transmission", {{"transmissionFactor", 1.0}}}}}};
  };
  Scene scene = load_boxes(dir, b, {with(volume), with(thin), with(clear)});
  ASSERT_EQ(scene.objects.size(), 3u);
  EXPECT_EQ(scene.objects[0].interior.kind, InteriorKind::constant);
  EXPECT_NEAR(scene.objects[0].interior.sigma, std::log(2.0) / 2.0, 1e-12);
  EXPECT_DOUBLE_EQ(scene.objects[0].material.alpha, 0.0);
  EXPECT_EQ(scene.objects[1].interior.kind, InteriorKind::none);
  EXPECT_EQ(scene.objects[2].interior.kind, InteriorKind::constant);  // infinite distance
  EXPECT_DOUBLE_EQ(scene.objects[2].interior.sigma, 0.0);
}

TEST(GltfMaterials, ColouredAttenuationTintsPerChannelAndShadowsUseTheMean) {
  ScratchDir dir;
  GltfBuilder b;
  int m = b.add_material({{"extensions",
                           {{"KHR_materials_volume",
                             {{"thicknessFactor", 1.0},
                              {"attenuationColor", {0.5, 0.25, 1.0}},
                              {"attenuationDistance", 1.0}}}}}});
  int mesh = test::add_box_mesh(b, {{"material", m}});
  b.add_node({{"mesh", mesh}});
  b.add_node({{"mesh", mesh}, {"translation", {3, 0, 0}}});
  Scene scene = load_gltf_scene(b.write_gltf(dir.file("tinted.gltf")));
  ASSERT_EQ(scene.objects.size(), 2u);
  // Channel extinctions ln 2, 2 ln 2 and 0: mean ln 2 for shadows, per channel for the camera.
  const Interior& in = scene.objects[1].interior;
  EXPECT_NEAR(in.sigma, std::log(2.0), 1e-12);
  EXPECT_NEAR(in.sigma * in.sigma_tint.x, std::log(2.0), 1e-12);
  EXPECT_NEAR(in.sigma * in.sigma_tint.y, 2.0 * std::log(2.0), 1e-12);
  EXPECT_DOUBLE_EQ(in.sigma * in.sigma_tint.z, 0.0);
}

TEST(GltfMaterials, TransmissivePartKeepsTheBaseColourForTheCameraPass) {
  ScratchDir dir;
  GltfBuilder b;
  b.use_extension("KHR_materials_transmission");
  auto glass = [](double transmission, const char* mode, double coverage) {
    return json{
        {"alphaMode", mode},
        {"pbrMetallicRoughness", {{"baseColorFactor", {0.9, 0.3, 0.2, coverage}}}},
        {"extensions", {{"KHR_materials_transmission", {{"transmissionFactor", transmission}}}}}};
  };
  Scene scene = load_boxes(
      dir, b, {glass(1.0, "OPAQUE", 1.0), glass(0.25, "BLEND", 0.5), glass(0, "OPAQUE", 1)});
  EXPECT_DOUBLE_EQ(scene.objects[0].material.alpha, 0.0);  // shadows: unchanged mapping
  EXPECT_DOUBLE_EQ(scene.objects[0].material.transmission, 1.0);
  EXPECT_DOUBLE_EQ(scene.objects[1].material.alpha, 0.375);  // 0.5 * (1 - 0.25)
  EXPECT_DOUBLE_EQ(scene.objects[1].material.transmission, 0.125);
  EXPECT_DOUBLE_EQ(scene.objects[2].material.transmission, 0.0);
  EXPECT_DOUBLE_EQ(scene.objects[0].material.color.x, 0.9);
}

TEST(GltfMaterials, PhongFromRoughness) {
  ScratchDir dir;
  GltfBuilder b;
  Scene scene = load_boxes(dir, b,
                           {{{"pbrMetallicRoughness", {{"roughnessFactor", 0.5}}}},
                            {{"pbrMetallicRoughness", {{"roughnessFactor", 0.0}}}}});
  const Material& half = scene.objects[0].material;
  EXPECT_DOUBLE_EQ(half.diffuse, 0.8);
  EXPECT_DOUBLE_EQ(half.specular, 0.14);
  EXPECT_DOUBLE_EQ(half.shininess, 30.0);  // 2 / 0.5^4 - 2
  EXPECT_DOUBLE_EQ(scene.objects[1].material.shininess, 512.0);
  EXPECT_DOUBLE_EQ(scene.objects[1].material.specular, 0.24);

  GltfBuilder plain;  // no material: glTF's default, white and fully rough
  plain.add_node({{"mesh", test::add_box_mesh(plain)}});
  Material fallback = load_gltf_scene(plain.write_gltf(dir.file("plain.gltf"))).objects[0].material;
  EXPECT_DOUBLE_EQ(fallback.color.x, 1.0);
  EXPECT_DOUBLE_EQ(fallback.specular, 0.04);
  EXPECT_DOUBLE_EQ(fallback.shininess, 1.0);
  EXPECT_DOUBLE_EQ(fallback.alpha, 1.0);
}

TEST(GltfErrors, InteriorOnAnOpenMeshIsRejected) {
  ScratchDir dir;
  GltfBuilder b;
  int m = b.add_material({{"extensions", {{"KHR_materials_volume", {{"thicknessFactor", 1}}}}}});
  int tri = b.add_positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
  b.add_node({{"mesh", b.add_mesh({{"attributes", {{"POSITION", tri}}}, {"material", m}})}});
  std::string path = b.write_gltf(dir.file("open.gltf"));
  expect_input_error([&] { load_gltf_scene(path); }, {path, "not closed"});
}

TEST(GltfErrors, UnsupportedExtensions) {
  ScratchDir dir;
  GltfBuilder b;
  b.add_node({{"mesh", test::add_box_mesh(b)}});
  b.use_extension("EXT_fancy_sparkles");
  int before = warning_count();
  load_gltf_scene(b.write_gltf(dir.file("used.gltf")));
  EXPECT_GT(warning_count(), before);
  b.use_extension("KHR_draco_mesh_compression", true);
  std::string path = b.write_gltf(dir.file("required.gltf"));
  expect_input_error([&] { load_gltf_scene(path); }, {path, "KHR_draco_mesh_compression"});
}

TEST(GltfErrors, AccessorRunningPastItsBufferView) {
  ScratchDir dir;
  GltfBuilder b;
  b.add_node({{"mesh", test::add_box_mesh(b)}});
  b.doc["accessors"][0]["count"] = 25;  // the view holds 24 positions
  std::string path = b.write_gltf(dir.file("count.gltf"));
  expect_input_error([&] { load_gltf_scene(path); }, {path, "accessor 0", "POSITION", "run past"});
  b.doc["accessors"][0]["count"] = 24;
  b.doc["bufferViews"][0]["byteLength"] = 4096;  // past the end of the buffer
  path = b.write_gltf(dir.file("view.gltf"));
  expect_input_error([&] { load_gltf_scene(path); }, {path, "buffer view 0", "buffer 0"});
  b.doc["bufferViews"][0]["byteLength"] = 288;
  b.doc["accessors"][0]["type"] = "VEC2";
  path = b.write_gltf(dir.file("type.gltf"));
  expect_input_error([&] { load_gltf_scene(path); }, {path, "FLOAT VEC3"});
}

TEST(GltfErrors, IndexOutOfRangeAndNonFinitePosition) {
  ScratchDir dir;
  GltfBuilder b;
  int pos = b.add_positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
  int idx = b.add_indices({0, 1, 3});
  b.add_node({{"mesh", b.add_mesh({{"attributes", {{"POSITION", pos}}}, {"indices", idx}})}});
  std::string path = b.write_gltf(dir.file("index.gltf"));
  expect_input_error([&] { load_gltf_scene(path); }, {path, "accessor 1", "index 2 is 3"});

  GltfBuilder nan;
  nan.add_node(
      {{"mesh",
        nan.add_mesh(
            {{"attributes", {{"POSITION", nan.add_positions({0, 0, 0, 1, NAN, 0, 0, 1, 0})}}}})}});
  path = nan.write_gltf(dir.file("nan.gltf"));
  expect_input_error([&] { load_gltf_scene(path); }, {path, "position 1 is not finite"});
}

TEST(GltfErrors, BadFiles) {
  ScratchDir dir;
  std::string missing = dir.file("missing.gltf");
  expect_input_error([&] { load_gltf_scene(missing); }, {missing, "not found"});

  std::string broken = dir.file("broken.gltf");
  test::write_text(broken, "{\"asset\": {\"version\": \"2.0\"}, \"nodes\": [");
  expect_input_error([&] { load_gltf_scene(broken); }, {broken, "cannot load glTF", "parse error"});

  GltfBuilder b;
  b.add_node({{"mesh", test::add_box_mesh(b)}});
  std::vector<unsigned char> glb = b.glb_bytes();
  glb.resize(glb.size() - 40);
  std::string truncated = dir.file("truncated.glb");
  test::write_bytes(truncated, glb);
  expect_input_error([&] { load_gltf_scene(truncated); }, {truncated, "truncated"});

  std::string text_glb = dir.file("text.glb");
  test::write_text(text_glb, b.doc.dump());
  expect_input_error([&] { load_gltf_scene(text_glb); }, {text_glb, "glTF"});
}

TEST(GltfErrors, BadHierarchyAndEmptyScene) {
  ScratchDir dir;
  GltfBuilder b;
  int mesh = test::add_box_mesh(b);
  b.add_node({{"mesh", mesh}, {"children", {1}}});
  b.add_node({{"children", {0}}}, false);
  std::string path = b.write_gltf(dir.file("cycle.gltf"));
  expect_input_error([&] { load_gltf_scene(path); }, {path, "node 0", "tree"});

  GltfBuilder points;
  int cloud = points.add_positions({0, 0, 0, 1, 1, 1});
  points.add_node(
      {{"mesh", points.add_mesh({{"attributes", {{"POSITION", cloud}}}, {"mode", 0}})}});
  path = points.write_gltf(dir.file("points.gltf"));
  expect_input_error([&] { load_gltf_scene(path); }, {path, "no triangle"});
}

}  // namespace
}  // namespace dv
