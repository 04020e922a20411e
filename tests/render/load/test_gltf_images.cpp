// glTF images that cannot be used and where image URIs may point: a missing, refused or
// undecodable base-colour image loads the model with one warning naming the image (the material
// draws its factor, as if untextured); URIs are relative references, percent-decoded, that must
// stay inside the model's folder. And KHR_texture_transform's rotation against a texel worked
// out by hand. External buffers (.bin) follow the same URI policy; one that is refused or
// missing fails the load with an error naming the file.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/log.h"
#include "engine/scene/texture_sampling.h"
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

// The 4 x 4 test image: texel (x, y) has sRGB bytes (40 + 50 x, 40 + 50 y, 7), all distinct.
std::vector<unsigned char> texel_bytes(int x, int y) {
  return {static_cast<unsigned char>(40 + 50 * x), static_cast<unsigned char>(40 + 50 * y), 7};
}

void write_test_png(const std::string& path) {
  std::vector<unsigned char> rgb;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      const std::vector<unsigned char> t = texel_bytes(x, y);
      rgb.insert(rgb.end(), t.begin(), t.end());
    }
  write_png_bytes(path, 4, 4, rgb);
}

// The unit quad (0,0,0)-(1,1,0) facing +z with TEXCOORD_0 (u, v) = (x, 1 - y), material
// `material`; `image` (if not null) is image 0 under texture 0 with a NEAREST, REPEAT sampler.
GltfBuilder quad(const json& material, const json& image) {
  GltfBuilder b;
  if (!image.is_null()) {
    b.doc["images"] = json::array({image});
    b.doc["samplers"] = json::array({{{"magFilter", 9728}, {"wrapS", 10497}, {"wrapT", 10497}}});
    b.doc["textures"] = json::array({{{"source", 0}, {"sampler", 0}}});
  }
  add_quad_node(b, material, true);
  return b;
}

json textured_material(const json& transform = nullptr) {
  json texture = {{"index", 0}};
  if (!transform.is_null()) texture["extensions"]["KHR_texture_transform"] = transform;
  return {{"pbrMetallicRoughness",
           {{"baseColorFactor", {0.2, 0.6, 0.9, 1.0}}, {"baseColorTexture", texture}}}};
}

json untextured_material() {
  return {{"pbrMetallicRoughness", {{"baseColorFactor", {0.2, 0.6, 0.9, 1.0}}}}};
}

// Loads the file, returning the scene, the warnings it logged and their text.
struct Loaded {
  Scene scene;
  int warnings = 0;
  std::string log;
};
Loaded load_logged(const std::string& path) {
  const int before = warning_count();
  testing::internal::CaptureStderr();
  Loaded out;
  try {
    out.scene = load_gltf_scene(path);
  } catch (...) {
    std::cerr << testing::internal::GetCapturedStderr();
    throw;
  }
  out.log = testing::internal::GetCapturedStderr();
  out.warnings = warning_count() - before;
  return out;
}

int occurrences(const std::string& text, const std::string& word) {
  int n = 0;
  for (size_t at = text.find(word); at != std::string::npos; at = text.find(word, at + 1)) ++n;
  return n;
}

Image render(const Scene& scene) {
  const SceneData data(scene, Memory::host);
  auto none = shadow_registry().create("none");
  return render_reference(Backend::cpu, data, scene.camera, *none, dvec3(0.0)).image;
}

// The scene's image of the material's factor alone (the same quad without a texture).
void expect_renders_like_untextured(Scene scene, const std::string& dir) {
  Scene plain =
      load_gltf_scene(quad(untextured_material(), nullptr).write_gltf(dir + "/plain.gltf"));
  scene.camera.width = plain.camera.width = 48;
  scene.camera.height = plain.camera.height = 36;
  const Image a = render(scene), b = render(plain);
  ASSERT_EQ(a.rgb.size(), b.rgb.size());
  EXPECT_EQ(a.rgb, b.rgb);
  EXPECT_GT(b.at(24, 18).z, 0.05);  // the quad is in view and lit
}

// A missing base-colour image no longer refuses the model: it loads with one warning naming the
// file, once although two materials use it, and draws the factor.
TEST(GltfImages, MissingBaseColourImageWarnsOnceAndDrawsTheFactor) {
  ScratchDir dir;
  GltfBuilder b = quad(textured_material(), {{"uri", "no-such-image.png"}});
  json second = b.doc["nodes"][0];
  second["translation"] = {2, 0, 0};
  b.add_node(second);
  b.doc["meshes"].push_back(b.doc["meshes"][0]);
  b.add_material(textured_material());
  b.doc["meshes"][1]["primitives"][0]["material"] = 1;
  b.doc["nodes"][1]["mesh"] = 1;
  const Loaded loaded = load_logged(b.write_gltf(dir.file("quad.gltf")));
  EXPECT_EQ(loaded.warnings, 1) << loaded.log;
  EXPECT_EQ(occurrences(loaded.log, "no-such-image.png"), 2) << loaded.log;  // uri and path
  EXPECT_NE(loaded.log.find("file not found"), std::string::npos) << loaded.log;
  EXPECT_NE(loaded.log.find(dir.file("no-such-image.png")), std::string::npos) << loaded.log;
  ASSERT_EQ(loaded.scene.objects.size(), 2u);
  for (const Object& o : loaded.scene.objects) {
    EXPECT_EQ(o.material.base_texture, -1);
    EXPECT_EQ(o.material.color, dvec3(0.2, 0.6, 0.9));
    EXPECT_EQ(o.material.alpha, 1.0);
  }
  EXPECT_TRUE(loaded.scene.textures.empty());
  EXPECT_TRUE(loaded.scene.meshes[0].corner_uvs.empty());
}

TEST(GltfImages, MissingImageRendersWithTheFactor) {
  ScratchDir dir;
  const Loaded loaded = load_logged(
      quad(textured_material(), {{"uri", "gone.png"}}).write_gltf(dir.file("quad.gltf")));
  expect_renders_like_untextured(loaded.scene, dir.file(""));
}

// A BLEND material whose image is missing takes its coverage from the factor alone.
TEST(GltfImages, MissingImageKeepsTheFactorsCoverage) {
  ScratchDir dir;
  json material = textured_material();
  material["pbrMetallicRoughness"]["baseColorFactor"][3] = 0.25;
  material["alphaMode"] = "BLEND";
  const Loaded loaded =
      load_logged(quad(material, {{"uri", "gone.png"}}).write_gltf(dir.file("quad.gltf")));
  EXPECT_EQ(loaded.scene.objects[0].material.alpha, 0.25);
}

// '..' steps that leave the model's folder are refused even though the file exists and is a
// valid image; the warning names the URI and the rule.
TEST(GltfImages, DotDotOutsideTheModelFolderIsRefused) {
  ScratchDir dir;
  std::filesystem::create_directories(dir.file("model"));
  write_test_png(dir.file("outside.png"));
  const Loaded loaded = load_logged(quad(textured_material(), {{"uri", "../outside.png"}})
                                        .write_gltf(dir.file("model/quad.gltf")));
  EXPECT_EQ(loaded.warnings, 1) << loaded.log;
  EXPECT_NE(loaded.log.find("../outside.png"), std::string::npos) << loaded.log;
  EXPECT_NE(loaded.log.find("leave the model's folder"), std::string::npos) << loaded.log;
  EXPECT_EQ(loaded.scene.objects[0].material.base_texture, -1);
  EXPECT_EQ(loaded.scene.objects[0].material.color, dvec3(0.2, 0.6, 0.9));
}

// An absolute path is refused as absolute (it used to read "not found" although it existed).
TEST(GltfImages, AbsolutePathIsRefusedAsAbsolute) {
  ScratchDir dir;
  write_test_png(dir.file("elsewhere.png"));
  const std::string absolute = std::filesystem::absolute(dir.file("elsewhere.png")).string();
  const Loaded loaded =
      load_logged(quad(textured_material(), {{"uri", absolute}}).write_gltf(dir.file("quad.gltf")));
  EXPECT_EQ(loaded.warnings, 1) << loaded.log;
  EXPECT_NE(loaded.log.find(absolute), std::string::npos) << loaded.log;
  EXPECT_NE(loaded.log.find("absolute path"), std::string::npos) << loaded.log;
  EXPECT_EQ(loaded.log.find("not found"), std::string::npos) << loaded.log;
  EXPECT_EQ(loaded.scene.objects[0].material.base_texture, -1);
}

TEST(GltfImages, UriWithASchemeIsRefused) {
  ScratchDir dir;
  const Loaded loaded = load_logged(quad(textured_material(), {{"uri", "file:///etc/hostname"}})
                                        .write_gltf(dir.file("quad.gltf")));
  EXPECT_EQ(loaded.warnings, 1) << loaded.log;
  EXPECT_NE(loaded.log.find("scheme 'file:'"), std::string::npos) << loaded.log;
  EXPECT_EQ(loaded.scene.objects[0].material.base_texture, -1);
}

// A file that is not an image: the warning names the file and says it cannot be decoded.
TEST(GltfImages, UndecodableImageNamesTheFile) {
  ScratchDir dir;
  test::write_text(dir.file("notes.png"), "these are notes, not pixels\n");
  const Loaded loaded = load_logged(
      quad(textured_material(), {{"uri", "notes.png"}}).write_gltf(dir.file("quad.gltf")));
  EXPECT_EQ(loaded.warnings, 1) << loaded.log;
  EXPECT_NE(loaded.log.find(dir.file("notes.png") + ": cannot be decoded"), std::string::npos)
      << loaded.log;
  expect_renders_like_untextured(loaded.scene, dir.file(""));
}

// Undecodable embedded data is the same: one warning naming the image, the factor drawn.
TEST(GltfImages, UndecodableEmbeddedImageWarns) {
  ScratchDir dir;
  const std::vector<unsigned char> junk = {'n', 'o', 't', ' ', 'a', ' ', 'p', 'n', 'g'};
  const Loaded loaded =
      load_logged(quad(textured_material(),
                       {{"uri", "data:image/png;base64," + test::base64(junk)}, {"name", "label"}})
                      .write_gltf(dir.file("quad.gltf")));
  EXPECT_EQ(loaded.warnings, 1) << loaded.log;
  EXPECT_NE(loaded.log.find("image 0 'label': cannot be decoded"), std::string::npos) << loaded.log;
  EXPECT_EQ(loaded.scene.objects[0].material.base_texture, -1);
}

// URIs are percent-decoded relative references; '..' that stays inside the folder is fine.
TEST(GltfImages, PercentEncodedUriInsideTheFolderLoads) {
  ScratchDir dir;
  std::filesystem::create_directories(dir.file("tex dir"));
  write_test_png(dir.file("tex dir/a+b #1.png"));
  const Loaded loaded =
      load_logged(quad(textured_material(), {{"uri", "tex%20dir/../tex%20dir/a+b%20%231.png"}})
                      .write_gltf(dir.file("quad.gltf")));
  EXPECT_EQ(loaded.warnings, 0) << loaded.log;
  ASSERT_EQ(loaded.scene.textures.size(), 1u);
  EXPECT_EQ(loaded.scene.textures[0].width, 4);
  EXPECT_EQ(loaded.scene.textures[0].rgba[4 * 5 + 0], 90);  // texel (1, 1)
}

// A JSON scene that imports a textured file keeps its textures (the objects index them).
TEST(GltfImages, JsonImportKeepsTheTextures) {
  ScratchDir dir;
  write_test_png(dir.file("grid.png"));
  quad(textured_material(), {{"uri", "grid.png"}}).write_gltf(dir.file("q.gltf"));
  test::write_text(dir.file("scene.json"), R"({"import": "q.gltf"})");
  const Scene scene = load_scene(dir.file("scene.json"));
  ASSERT_EQ(scene.textures.size(), 1u);
  EXPECT_EQ(scene.objects[0].material.base_texture, 0);
  EXPECT_EQ(scene.textures[0].width, 4);
}

// The colour the quad shows at mesh texture coordinates (u, v) (point (u, 1 - v, 0)).
dvec3 colour_at(const Scene& scene, double u, double v) {
  const SceneData data(scene, Memory::host);
  const SceneView& s = data.view();
  const dvec3 p(u, 1.0 - v, 0.0);
  for (uint32_t tri = 0; tri < uint32_t(s.triangles.size); ++tri) {
    const dvec3 w = triangle_weights(s, tri, p);
    if (w.x < 0.0 || w.y < 0.0 || w.z < 0.0) continue;
    return surface_look(s, s.objects[0], tri, p).color;
  }
  ADD_FAILURE() << "no triangle holds (" << u << ", " << v << ")";
  return dvec3(-1.0);
}

dvec3 linear_texel(const Scene& scene, int x, int y) {
  const SceneData data(scene, Memory::host);
  const std::vector<unsigned char> t = texel_bytes(x, y);
  const dvec3 factor(0.2, 0.6, 0.9);
  return factor * dvec3(data.view().srgb_to_linear[t[0]], data.view().srgb_to_linear[t[1]],
                        data.view().srgb_to_linear[t[2]]);
}

// KHR_texture_transform's own example: offset [0, 1], rotation pi/2, scale [0.5, 0.5] shows the
// image's lower-left quadrant turned 90 degrees clockwise: (u, v) -> (v / 2, 1 - u / 2).
// Mesh (0.9, 0.1) -> (0.05, 0.55): texel (0, 2); mesh (0.3, 0.7) -> (0.35, 0.85): texel (1, 3).
// The opposite turn would read (-0.05, 1.45) and (-0.35, 1.15): texels (3, 1) and (2, 0).
TEST(GltfImages, TextureTransformRotationTurnsAsTheSpecExample) {
  ScratchDir dir;
  write_test_png(dir.file("grid.png"));
  const json transform = {{"offset", {0.0, 1.0}}, {"rotation", kPi / 2}, {"scale", {0.5, 0.5}}};
  const Scene scene = load_gltf_scene(
      quad(textured_material(transform), {{"uri", "grid.png"}}).write_gltf(dir.file("q.gltf")));
  EXPECT_EQ(colour_at(scene, 0.9, 0.1), linear_texel(scene, 0, 2));
  EXPECT_EQ(colour_at(scene, 0.3, 0.7), linear_texel(scene, 1, 3));
}

// A rotation alone, 30 degrees: (u, v) -> (u cos + v sin, -u sin + v cos). Mesh (0.5, 0.5) ->
// (0.683, 0.183): texel (2, 0); the opposite turn would give (0.183, 0.683): texel (0, 2).
TEST(GltfImages, TextureTransformRotationAloneAgainstAKnownTexel) {
  ScratchDir dir;
  write_test_png(dir.file("grid.png"));
  const json transform = {{"rotation", kPi / 6}};
  const Scene scene = load_gltf_scene(
      quad(textured_material(transform), {{"uri", "grid.png"}}).write_gltf(dir.file("q.gltf")));
  EXPECT_EQ(colour_at(scene, 0.5, 0.5), linear_texel(scene, 2, 0));
  EXPECT_EQ(colour_at(scene, 0.1, 0.9), linear_texel(scene, 2, 2));  // (0.537, 0.729); not (2, 3)
}

// The load's error for a file whose buffer is refused or missing ("" if it loads).
std::string load_error(const std::string& path) {
  testing::internal::CaptureStderr();
  std::string message;
  try {
    load_gltf_scene(path);
  } catch (const InputError& e) {
    message = e.what();
  }
  testing::internal::GetCapturedStderr();
  return message;
}

// A .bin in a folder below the model's is read.
TEST(GltfBuffers, ExternalBufferBelowTheModelFolderLoads) {
  ScratchDir dir;
  std::filesystem::create_directories(dir.file("model/bins"));
  const Loaded loaded =
      load_logged(quad(untextured_material(), nullptr)
                      .write_gltf_external_bin(dir.file("model/quad.gltf"), "bins/quad.bin"));
  ASSERT_EQ(loaded.scene.meshes.size(), 1u);
  EXPECT_EQ(loaded.scene.meshes[0].positions.size(), 4u);
  EXPECT_EQ(loaded.scene.meshes[0].positions[2], dvec3(1.0, 1.0, 0.0));
}

// '..' steps out of the model's folder: refused although the file exists, the error names the
// model, the URI and the rule.
// The quad in DIR/model/quad.gltf with its buffer written to `uri` (relative to the model).
std::string quad_with_buffer_at(ScratchDir& dir, const std::string& uri) {
  std::filesystem::create_directories(dir.file("model"));
  return quad(untextured_material(), nullptr)
      .write_gltf_external_bin(dir.file("model/quad.gltf"), uri);
}

// The error loading `model` gives, checked to name each of `parts`.
std::string error_naming(const std::string& model, const std::vector<std::string>& parts) {
  const std::string error = load_error(model);
  for (const std::string& part : parts) EXPECT_NE(error.find(part), std::string::npos) << error;
  return error;
}

TEST(GltfBuffers, DotDotOutsideTheModelFolderIsRefused) {
  ScratchDir dir;
  const std::string model = quad_with_buffer_at(dir, "../outside.bin");
  ASSERT_TRUE(std::filesystem::exists(dir.file("outside.bin")));
  error_naming(model, {model, "buffer URI '../outside.bin'", "leave the model's folder"});
}

// An absolute path: refused as absolute, not "not found".
TEST(GltfBuffers, AbsolutePathIsRefusedAsAbsolute) {
  ScratchDir dir;
  const std::string absolute = std::filesystem::absolute(dir.file("elsewhere.bin")).string();
  const std::string model = quad_with_buffer_at(dir, absolute);
  ASSERT_TRUE(std::filesystem::exists(absolute));
  const std::string error = error_naming(model, {absolute, "absolute path"});
  EXPECT_EQ(error.find("buffer file not found"), std::string::npos) << error;
}

// A missing .bin names the file it looked for, and one in the working directory but not in the
// model's folder is not read (tinygltf's own fallback would read it).
TEST(GltfBuffers, MissingBufferNamesTheFileAndTheWorkingDirectoryIsNotSearched) {
  ScratchDir dir;
  const std::string model = quad_with_buffer_at(dir, "quad.bin");
  std::filesystem::rename(dir.file("model/quad.bin"), dir.file("quad.bin"));
  const std::filesystem::path was = std::filesystem::current_path();
  std::filesystem::current_path(dir.file(""));
  const std::string error = load_error(std::filesystem::absolute(model).string());
  std::filesystem::current_path(was);
  EXPECT_NE(error.find((std::filesystem::absolute(model).parent_path() / "quad.bin").string() +
                       ": buffer file not found"),
            std::string::npos)
      << error;
}

TEST(GltfBuffers, UriWithASchemeIsRefused) {
  ScratchDir dir;
  const std::string model = quad(untextured_material(), nullptr)
                                .write_gltf_external_bin(dir.file("quad.gltf"), "quad.bin");
  std::string text;
  {
    std::ifstream in(model);
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  const size_t at = text.find("\"quad.bin\"");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 10, "\"file:///etc/hostname\"");
  std::ofstream(model) << text;
  const std::string error = load_error(model);
  EXPECT_NE(error.find("scheme 'file:'"), std::string::npos) << error;
}

}  // namespace
}  // namespace dv
