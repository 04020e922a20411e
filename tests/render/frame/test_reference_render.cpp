// The renderers against closed forms: a lit plane's Phong value (ray walk and rasterizer), and
// the shadow of a constant-extinction sphere equal to the oracle at the shaded points; plus the
// multi-frame orbit.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/oracle/transmittance.h"
#include "engine/raster/camera_rays.h"
#include "render/frame/raster_render.h"
#include "render/frame/reference_render.h"
#include "tests/support/scene_builder.h"

namespace dv {
namespace {

using test::SceneBuilder;

// Looking straight down at a 10x10 floor (y = 0) from (0, 4, 0).
Camera top_camera(int size) {
  Camera c;
  c.position = {0.0, 4.0, 0.0};
  c.target = {0.0, 0.0, 0.0};
  c.up = {0.0, 0.0, -1.0};
  c.fov_deg = 60.0;
  c.width = c.height = size;
  return c;
}

dvec3 floor_point(const Camera& cam, int x, int y) {
  const CameraView v = make_camera_view(cam);
  const dvec3 d = camera_ray_direction(v, x, y);
  return cam.position + d * (-cam.position.y / d.y);
}

TEST(ReferenceRender, LitPlaneMatchesPhong) {
  SceneBuilder b;
  Object& floor = b.add(make_quad(10.0));
  floor.material = {dvec3(0.6, 0.5, 0.4), 0.1, 0.7, 0.3, 20.0, 1.0};
  Light& l = b.omni({1.0, 3.0, 0.5});
  l.intensity = 9.0;
  const SceneData data = b.build();
  const Camera cam = top_camera(32);
  auto none = shadow_registry().create("none");
  const RenderResult r = render_reference(Backend::cpu, data, cam, *none, dvec3(0.0));
  const RenderResult raster = render_raster(Backend::cpu, data, cam, *none, dvec3(0.0)).render;
  for (auto [x, y] : {std::pair{16, 16}, std::pair{3, 7}, std::pair{25, 28}}) {
    const dvec3 p = floor_point(cam, x, y);
    const dvec3 n(0.0, 1.0, 0.0), to_light = glm::normalize(l.position - p);
    const dvec3 to_eye = glm::normalize(cam.position - p);
    const double falloff = l.intensity / glm::dot(l.position - p, l.position - p);
    const dvec3 refl = 2.0 * glm::dot(n, to_light) * n - to_light;
    const double spec = 0.3 * std::pow(std::max(0.0, glm::dot(refl, to_eye)), 20.0);
    const dvec3 expected =
        0.1 * floor.material.color +
        falloff * (0.7 * glm::dot(n, to_light) * floor.material.color + dvec3(spec));
    for (const RenderResult* image : {&r, &raster}) {
      const dvec3 got = image->image.at(x, y);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], expected[c], 1e-5) << x << "," << y;
    }
  }
  EXPECT_EQ(r.counters.overflow_pixels, 0u);
  EXPECT_EQ(r.counters.max_hits, 1u);
  EXPECT_EQ(raster.counters.max_hits, 1u);
}

TEST(ReferenceRender, SphereShadowEqualsOracle) {
  SceneBuilder b;
  Object& floor = b.add(make_quad(10.0));
  floor.material = {dvec3(1.0), 0.0, 1.0, 0.0, 1.0, 1.0};
  Object& sphere = b.add(make_icosphere(0.8, 3), 0.0, InteriorKind::constant, 1.2);
  sphere.transform[3] = dvec4(0.2, 1.5, 0.0, 1.0);
  b.omni({4.0, 6.0, 0.0});  // from the side, so the camera sees the shadow beside the sphere
  const SceneData data = b.build();
  const Camera cam = top_camera(48);
  auto none = shadow_registry().create("none");
  auto reference = shadow_registry().create("reference");
  const RenderResult lit = render_reference(Backend::cpu, data, cam, *none, dvec3(0.0));
  const RenderResult shadowed = render_reference(Backend::cpu, data, cam, *reference, dvec3(0.0));
  int in_shadow = 0;
  for (int y = 0; y < 48; y += 3)
    for (int x = 0; x < 48; x += 3) {
      const dvec3 p = floor_point(cam, x, y);
      // Pixels whose view ray crosses the sphere see it attenuated: compare only the others.
      const CameraView v = make_camera_view(cam);
      const ShearedRay ray = make_sheared_ray(cam.position, camera_ray_direction(v, x, y));
      bool crosses = false;
      for_each_hit(data.view(), ray, 0.0, 1e9, [&](const RayHit& h) {
        crosses |= data.view().triangle_object[h.triangle] == 1;
        return true;
      });
      if (crosses) continue;
      const double t = exact_transmittance(data.view(), data.view().lights[0], p).transmittance;
      const double ratio = shadowed.image.at(x, y).x / lit.image.at(x, y).x;
      EXPECT_NEAR(ratio, t, 1e-5) << x << "," << y;
      in_shadow += t < 0.9;
    }
  EXPECT_GT(in_shadow, 3);
}

TEST(ReferenceRender, OrbitCameraKeepsDistanceAndTarget) {
  Camera c;
  c.position = {0.0, 1.0, 5.0};
  c.target = {0.0, 1.0, 0.0};
  const Camera quarter = orbit_camera(c, 360.0, 1, 4);
  EXPECT_NEAR(quarter.position.x, 5.0, 1e-12);
  EXPECT_NEAR(quarter.position.z, 0.0, 1e-12);
  EXPECT_NEAR(quarter.position.y, 1.0, 1e-12);
  EXPECT_EQ(orbit_camera(c, 90.0, 0, 3).position, c.position);
}

}  // namespace
}  // namespace dv
