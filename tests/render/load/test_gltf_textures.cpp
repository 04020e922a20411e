// glTF textures: base-colour images decoded from data: URIs, external files and .glb
// buffer views with their samplers; TEXCOORD and NORMAL read per triangle corner; MASK and
// BLEND kept for per-point coverage; normal maps loaded with a warning (images that cannot be
// used: tests/render/load/test_gltf_images.cpp). And the committed textured stand-in
// (tests/data/textured/textured_sphere.glb) renders with its base colour and smooth vertex
// normals.
#include <cmath>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/log.h"
#include "experiments/source_paths.h"
#include "render/frame/reference_render.h"
#include "render/load/gltf_import.h"
#include "strategies/shadow/shadow_method.h"
#include "tests/render/load/gltf_builder.h"

namespace dv {
namespace {

using test::GltfBuilder;
using test::json;
using test::ScratchDir;

std::string standin(const std::string& name) {
  return test::source_dir() + "/tests/data/textured/" + name;
}

std::vector<unsigned char> file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A unit quad with TEXCOORD_0 whose material uses texture 0 through `image` (the caller adds
// the image) with a NEAREST, CLAMP sampler.
GltfBuilder textured_quad(const json& image, const std::string& alpha_mode) {
  GltfBuilder b;
  json material = {
      {"pbrMetallicRoughness",
       {{"baseColorFactor", {1.0, 1.0, 1.0, 0.5}}, {"baseColorTexture", {{"index", 0}}}}},
      {"alphaMode", alpha_mode}};
  b.doc["images"] = json::array({image});
  b.doc["samplers"] = json::array({{{"magFilter", 9728}, {"wrapS", 33071}, {"wrapT", 33648}}});
  b.doc["textures"] = json::array({{{"source", 0}, {"sampler", 0}}});
  add_quad_node(b, material, true);
  return b;
}

// The stand-in's 8 x 8 cut-out texture as a data: URI.
json embedded_image() {
  return {{"uri", "data:image/png;base64," + test::base64(file_bytes(standin("alpha_mask.png")))}};
}

TEST(GltfTextures, DataUriImageDecodesWithItsSampler) {
  ScratchDir dir;
  GltfBuilder b = textured_quad(embedded_image(), "BLEND");
  const Scene scene = load_gltf_scene(b.write_gltf(dir.file("quad.gltf")));
  ASSERT_EQ(scene.textures.size(), 1u);
  const Texture& t = scene.textures[0];
  EXPECT_EQ(t.width, 8);
  EXPECT_EQ(t.height, 8);
  EXPECT_EQ(t.filter, TextureFilter::nearest);
  EXPECT_EQ(t.wrap_s, TextureWrap::clamp);
  EXPECT_EQ(t.wrap_t, TextureWrap::mirror);
  // Texel (0, 0) is cut out, texel (7, 0) opaque red (make_textured_standins.py).
  EXPECT_EQ(t.rgba[3], 0);
  EXPECT_EQ(t.rgba[7 * 4 + 0], 200);
  EXPECT_EQ(t.rgba[7 * 4 + 3], 255);
  const Material& m = scene.objects[0].material;
  EXPECT_EQ(m.base_texture, 0);
  EXPECT_EQ(m.alpha_mode, AlphaMode::blend);
  EXPECT_EQ(m.coverage_factor, 0.5);
  EXPECT_EQ(m.alpha, 1.0);  // full coverage's opacity; the texel and factor scale it per point
  const TriangleMesh& mesh = scene.meshes[0];
  ASSERT_EQ(mesh.corner_uvs.size(), 6u);
  EXPECT_EQ(mesh.corner_uvs[1], dvec2(1.0, 1.0));  // the first triangle's second corner
}

TEST(GltfTextures, GlbImageNormalsAndNormalMapWarning) {
  const int warnings = warning_count();
  const Scene scene = load_gltf_scene(standin("textured_sphere.glb"));
  EXPECT_GT(warning_count(), warnings);  // normalTexture is ignored, with a warning
  ASSERT_EQ(scene.textures.size(), 1u);
  EXPECT_EQ(scene.textures[0].width, 16);
  const TriangleMesh& sphere = scene.meshes[size_t(scene.objects[0].mesh)];
  ASSERT_EQ(sphere.corner_normals.size(), 3 * sphere.triangles.size());
  ASSERT_EQ(sphere.corner_uvs.size(), 3 * sphere.triangles.size());
  for (size_t c = 0; c < sphere.corner_normals.size(); c += 37)
    EXPECT_NEAR(glm::length(sphere.corner_normals[c]), 1.0, 1e-6);
}

TEST(GltfTextures, TextureWithoutTexcoordsIsAnError) {
  ScratchDir dir;
  GltfBuilder b = textured_quad(embedded_image(), "MASK");
  b.doc["meshes"][0]["primitives"][0]["attributes"].erase("TEXCOORD_0");
  EXPECT_THROW(load_gltf_scene(b.write_gltf(dir.file("quad.gltf"))), InputError);
}

Image render(const Scene& scene) {
  const SceneData data(scene, Memory::host);
  auto none = shadow_registry().create("none");
  return render_reference(Backend::cpu, data, scene.camera, *none, dvec3(0.0)).image;
}

// Sum over the sphere's pixels of |second difference| down each column: a faceted sphere lit
// from above steps at every ring of facets, a smooth one changes gradually.
double vertical_roughness(const Image& image) {
  double sum = 0.0;
  for (int x = 26; x <= 38; ++x)
    for (int y = 18; y <= 46; ++y) {
      const double d = image.at(x, y + 1).y - 2.0 * image.at(x, y).y + image.at(x, y - 1).y;
      sum += std::abs(d);
    }
  return sum;
}

TEST(GltfTextures, TexturedSphereShowsItsColoursAndSmoothNormals) {
  Scene scene = load_gltf_scene(standin("textured_sphere.glb"));
  scene.camera.width = 64;
  scene.camera.height = 64;
  const Image image = render(scene);
  // The camera's right (x > 0) shows the texture's green half, its left the blue half.
  for (int y : {24, 28, 36}) {
    const dvec3 right = image.at(40, y), left = image.at(24, y);
    EXPECT_GT(right.y, 2.0 * right.z) << "row " << y;
    EXPECT_GT(right.y, 2.0 * right.x) << "row " << y;
    EXPECT_GT(left.z, 2.0 * left.y) << "row " << y;
    EXPECT_GT(left.z, 2.0 * left.x) << "row " << y;
  }
  Scene faceted = scene;
  for (TriangleMesh& m : faceted.meshes) m.corner_normals.clear();
  const double smooth = vertical_roughness(image), flat = vertical_roughness(render(faceted));
  EXPECT_LT(smooth, 0.5 * flat) << "smooth " << smooth << ", faceted " << flat;
}

}  // namespace
}  // namespace dv
