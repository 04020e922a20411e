// Texture sampling as kernels see it (engine/scene/texture_sampling.h): wrap modes, nearest and
// bilinear filtering of sRGB-decoded texels, KHR_texture_transform, MASK and BLEND coverage,
// interpolated vertex normals; and corner attributes that follow their vertices through the
// mesh repairs (merging duplicates, orienting outward).
#include <gtest/gtest.h>

#include <cmath>

#include "engine/scene/mesh_topology.h"
#include "engine/scene/scene_view.h"
#include "engine/scene/texture_sampling.h"

namespace dv {
namespace {

// A unit quad in the z = 0 plane (u along x, v along y) with a 2 x 1 texture: left texel red
// and opaque, right texel green with alpha 51 (0.2).
Scene textured_quad(TextureWrap wrap, TextureFilter filter, AlphaMode mode) {
  Scene s;
  s.source = "texture-test";
  TriangleMesh quad;
  quad.name = "quad";
  quad.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  quad.triangles = {{0, 1, 2}, {0, 2, 3}};
  quad.corner_uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1}};
  s.meshes.push_back(quad);
  Texture t;
  t.name = "two texels";
  t.width = 2;
  t.height = 1;
  t.rgba = {255, 0, 0, 255, 0, 255, 0, 51};
  t.wrap_s = t.wrap_t = wrap;
  t.filter = filter;
  s.textures.push_back(t);
  Object o;
  o.name = "quad";
  o.mesh = 0;
  o.material.color = dvec3(1.0, 0.5, 1.0);
  o.material.base_texture = 0;
  o.material.alpha_mode = mode;
  o.material.alpha_cutoff = 0.5;
  s.objects.push_back(o);
  validate_scene(s);
  return s;
}

dvec4 sample(const SceneData& data, double u, double v) {
  const SceneView& s = data.view();
  return sample_texture(s, s.textures[0], dvec2(u, v));
}

TEST(TextureSampling, WrapModesPickTheTexelTheSpecSays) {
  const SceneData repeat(
      textured_quad(TextureWrap::repeat, TextureFilter::nearest, AlphaMode::opaque), Memory::host);
  const SceneData clamp(
      textured_quad(TextureWrap::clamp, TextureFilter::nearest, AlphaMode::opaque), Memory::host);
  const SceneData mirror(
      textured_quad(TextureWrap::mirror, TextureFilter::nearest, AlphaMode::opaque), Memory::host);
  EXPECT_EQ(sample(repeat, 0.25, 0.5), dvec4(1, 0, 0, 1));
  EXPECT_EQ(sample(repeat, 0.75, 0.5).y, 1.0);
  EXPECT_EQ(sample(repeat, 1.25, 0.5).x, 1.0);   // wraps to the left texel
  EXPECT_EQ(sample(repeat, -0.25, 0.5).y, 1.0);  // negative u wraps too
  EXPECT_EQ(sample(clamp, 1.25, 0.5).y, 1.0);    // stays on the right edge
  EXPECT_EQ(sample(clamp, -3.0, 0.5).x, 1.0);
  EXPECT_EQ(sample(mirror, 1.25, 0.5).y, 1.0);  // 1.25 mirrors to 0.75
  EXPECT_EQ(sample(mirror, 1.75, 0.5).x, 1.0);  // and 1.75 to 0.25
  EXPECT_NEAR(sample(repeat, 0.75, 0.5).w, 0.2, 1e-15);
}

TEST(TextureSampling, BilinearBlendsDecodedTexels) {
  const SceneData data(textured_quad(TextureWrap::clamp, TextureFilter::bilinear, AlphaMode::blend),
                       Memory::host);
  // Halfway between the texel centres: the mean of the linear values (sRGB 255 decodes to 1).
  const dvec4 mid = sample(data, 0.5, 0.5);
  EXPECT_DOUBLE_EQ(mid.x, 0.5);
  EXPECT_DOUBLE_EQ(mid.y, 0.5);
  EXPECT_DOUBLE_EQ(mid.w, 0.5 * (1.0 + 0.2));
  // sRGB 128 decodes to about 0.2159 (not 128 / 255): the table is the IEC formula.
  const SceneView& s = data.view();
  EXPECT_NEAR(s.srgb_to_linear[128], std::pow((128 / 255.0 + 0.055) / 1.055, 2.4), 1e-15);
}

TEST(TextureSampling, MaskCutsAndBlendScalesCoverage) {
  const dvec3 left(0.25, 0.5, 0.0), right(0.75, 0.5, 0.0);
  for (AlphaMode mode : {AlphaMode::opaque, AlphaMode::mask, AlphaMode::blend}) {
    const SceneData data(textured_quad(TextureWrap::clamp, TextureFilter::nearest, mode),
                         Memory::host);
    const SceneView& s = data.view();
    const ObjectView& o = s.objects[0];
    uint32_t tri_left = 0, tri_right = 0;  // BVH order: find each point's triangle
    for (uint32_t t = 0; t < 2; ++t) {
      const dvec3 w = triangle_weights(s, t, right);
      if (w.x >= 0 && w.y >= 0 && w.z >= 0) tri_right = t;
      const dvec3 wl = triangle_weights(s, t, left);
      if (wl.x >= 0 && wl.y >= 0 && wl.z >= 0) tri_left = t;
    }
    const SurfaceLook l = surface_look(s, o, tri_left, left),
                      r = surface_look(s, o, tri_right, right);
    EXPECT_EQ(l.alpha, 1.0);
    EXPECT_EQ(l.color, dvec3(1.0, 0.0, 0.0));  // factor (1, .5, 1) times red
    EXPECT_EQ(r.color, dvec3(0.0, 0.5, 0.0));
    const double expected = mode == AlphaMode::opaque ? 1.0 : mode == AlphaMode::mask ? 0.0 : 0.2;
    EXPECT_NEAR(r.alpha, expected, 1e-15);
    EXPECT_EQ(surface_alpha(s, tri_right, right), r.alpha);
  }
}

TEST(TextureSampling, TextureTransformMovesTheLookup) {
  Scene scene = textured_quad(TextureWrap::repeat, TextureFilter::nearest, AlphaMode::opaque);
  scene.objects[0].material.uv_transform[2] = glm::dvec3(0.5, 0.0, 1.0);  // offset u by 0.5
  const SceneData data(scene, Memory::host);
  const SceneView& s = data.view();
  const dvec3 left(0.25, 0.1, 0.0);
  for (uint32_t t = 0; t < 2; ++t) {
    const dvec3 w = triangle_weights(s, t, left);
    if (w.x >= 0 && w.y >= 0 && w.z >= 0)
      EXPECT_EQ(surface_look(s, s.objects[0], t, left).color, dvec3(0.0, 0.5, 0.0));
  }
}

TEST(TextureSampling, UntexturedScenesCarryNoTextureArrays) {
  Scene scene = textured_quad(TextureWrap::repeat, TextureFilter::nearest, AlphaMode::opaque);
  scene.objects[0].material.base_texture = -1;
  scene.textures.clear();
  scene.meshes[0].corner_uvs.clear();
  const SceneData data(scene, Memory::host);
  const SceneView& s = data.view();
  EXPECT_EQ(s.corner_uvs.size, 0);
  EXPECT_EQ(s.corner_normals.size, 0);
  EXPECT_EQ(s.texels.size, 0);
  EXPECT_EQ(s.srgb_to_linear.size, 0);
  EXPECT_EQ(surface_look(s, s.objects[0], 0, dvec3(0.25, 0.5, 0.0)).alpha, 1.0);
}

TEST(TextureSampling, VertexNormalsInterpolateAndFaceTheGeometricSide) {
  Scene scene = textured_quad(TextureWrap::repeat, TextureFilter::nearest, AlphaMode::opaque);
  const dvec3 tilt_left = glm::normalize(dvec3(-1, 0, 1)),
              tilt_right = glm::normalize(dvec3(1, 0, 1));
  scene.meshes[0].corner_normals = {tilt_left, tilt_right, tilt_right,
                                    tilt_left, tilt_right, tilt_left};
  const SceneData data(scene, Memory::host);
  const SceneView& s = data.view();
  const dvec3 centre(0.5, 0.5, 0.0);
  for (uint32_t t = 0; t < 2; ++t) {
    const dvec3 n = shading_normal(s, t, centre, dvec3(0, 0, 1));
    EXPECT_NEAR(n.x, 0.0, 1e-12);
    EXPECT_NEAR(n.z, 1.0, 1e-12);
    // Seen from the back (geometric normal flipped), the shading normal flips with it.
    EXPECT_NEAR(shading_normal(s, t, centre, dvec3(0, 0, -1)).z, -1.0, 1e-12);
  }
}

TEST(CornerAttributes, FollowTheirVerticesThroughRepairs) {
  // A tetrahedron with every face wound inward and duplicated corner positions; each corner's
  // UV is its position's x and y, so a corner that lost its vertex would show it.
  const dvec3 p[4] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const int faces[4][3] = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};  // outward
  TriangleMesh m;
  m.name = "tetra";
  for (const auto& f : faces) {
    const uint32_t base = uint32_t(m.positions.size());
    for (int k : {0, 2, 1}) {  // inward: reversed
      m.positions.push_back(p[f[k]]);
      m.corner_uvs.push_back(dvec2(p[f[k]].x, p[f[k]].y));
      m.corner_normals.push_back(p[f[k]]);
    }
    m.triangles.push_back({base, base + 1, base + 2});
  }
  merge_duplicate_vertices(m);
  ASSERT_EQ(m.positions.size(), 4u);
  orient_outward(m);
  ASSERT_EQ(m.corner_uvs.size(), 12u);
  ASSERT_EQ(m.corner_normals.size(), 12u);
  EXPECT_GT(signed_volume(m), 0.0);
  for (size_t t = 0; t < m.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const dvec3& q = m.positions[m.triangles[t][k]];
      EXPECT_EQ(m.corner_uvs[3 * t + size_t(k)], dvec2(q.x, q.y));
      EXPECT_EQ(m.corner_normals[3 * t + size_t(k)], q);
    }
}

}  // namespace
}  // namespace dv
