// Contact shadows on the staged ground (engine/scene/default_staging.h): a model staged without
// lights rests on a ground kGroundGapRadii below its bounds, so its bottom faces are casters
// between the light and the ground in the exact oracle. A translucent bottom face (a red glass
// cube) or a BLEND layer lying on the ground must shadow the ground in the maps too, which holds
// when the gap is wider than the maps' receiver bias there (engine/raster/light_faces.h,
// receiver_depth): dsm within 0.02 of the oracle per channel at ground points under them, for
// the staged key (spot) and fill (directional) lights, on CPU and CUDA, also with dsm's
// bilinear filter, and shadowmap's glass layer for the cube. The fill's orthographic map holds
// the ground but is fitted to the model (engine/raster/fitted_light_faces.h): fitted to the
// ground six radii wide, its slope bias on the ground at 25 degrees exceeded the gap.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "engine/raster/fitted_light_faces.h"
#include "engine/raster/light_faces.h"
#include "engine/scene/default_staging.h"
#include "render/load/mesh_generators.h"
#include "strategies/shadow/probe.h"
#include "tests/support/backends.h"
#include "tests/support/shadow_methods.h"

namespace dv {
namespace {

// `model` staged as a model viewer would (default camera, ground, key and fill lights).
Scene staged(const TriangleMesh& mesh, const Material& material) {
  Scene scene;
  scene.source = "contact-test";
  scene.meshes.push_back(mesh);
  Object o;
  o.name = "model";
  o.mesh = 0;
  o.material = material;
  scene.objects.push_back(o);
  scene.camera = default_camera(world_bounds(scene));
  EXPECT_TRUE(stage_scene(scene, {}));
  validate_scene(scene);
  return scene;
}

double ground_height(const Scene& scene) {
  for (const Object& o : scene.objects)
    if (o.name == "ground") return scene.meshes[size_t(o.mesh)].positions[0].y;
  ADD_FAILURE() << "no ground";
  return 0.0;
}

// Ground points under the middle of the unit square footprint [-0.5, 0.5]^2.
std::vector<dvec3> ground_points_under(const Scene& scene) {
  const double y = ground_height(scene);
  std::vector<dvec3> points;
  for (int i = -2; i <= 2; ++i)
    for (int j = -2; j <= 2; ++j) points.push_back({0.15 * i, y, 0.15 * j});
  return points;
}

// The answer at point i for light 0 (the staged key) or 1 (the fill).
const dvec3& answer(const ProbeResults& r, size_t i, int light = 0) {
  return r.rgb[i * size_t(r.light_count) + size_t(light)];
}

// Every point's per-channel transmittance of both staged lights from `method` within
// `tolerance` of the oracle's, except at a point whose oracle answer changes by more than half
// the tolerance within 0.005 of it (its light ray passes within a few texels of a caster's
// edge, where the exit face and so the glass's angle of incidence change: a texel's answer is
// its centre's). At most 2 of the 50 (point, light) pairs may be such edge points.
void expect_near_oracle(Backend backend, const Scene& scene, const std::string& method,
                        const std::string& params, double tolerance) {
  const SceneData data(scene, backend == Backend::cuda ? Memory::device : Memory::host);
  const SceneData host(scene, Memory::host);
  const std::vector<dvec3> points = ground_points_under(scene);
  std::vector<dvec3> around;
  const double step = 0.005;
  for (const dvec3& p : points)
    for (const dvec3& d :
         {dvec3(step, 0, 0), dvec3(-step, 0, 0), dvec3(0, 0, step), dvec3(0, 0, -step)})
      around.push_back(p + d);
  auto reference = test::make_shadow_method("reference", "");
  const ProbeResults exact = probe_transmittance(Backend::cpu, host, *reference, points);
  const ProbeResults exact_around = probe_transmittance(Backend::cpu, host, *reference, around);
  auto m = test::make_shadow_method(method, params);
  const ProbeResults r = probe_transmittance(backend, data, *m, points);
  ASSERT_EQ(r.light_count, 2);
  int edge_points = 0;
  for (int light = 0; light < 2; ++light)
    for (size_t i = 0; i < points.size(); ++i) {
      double change = 0.0;
      for (size_t k = 0; k < 4; ++k)
        for (int c = 0; c < 3; ++c)
          change = std::max(change, std::abs(answer(exact_around, 4 * i + k, light)[c] -
                                             answer(exact, i, light)[c]));
      if (change > 0.5 * tolerance) {
        ++edge_points;
        continue;
      }
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(answer(r, i, light)[c], answer(exact, i, light)[c], tolerance)
            << method << " " << params << " light " << light << " point " << i << " channel " << c;
    }
  std::printf("%s %s: %d of 50 (point, light) pairs at a caster's edge, not compared\n",
              method.c_str(), params.c_str(), edge_points);
  EXPECT_LE(edge_points, 2) << method << " " << params;
}

class ContactShadows : public ::testing::TestWithParam<Backend> {};

TEST_P(ContactShadows, RedGlassCubeRestingOnTheGroundKeepsBothCrossings) {
  DV_SKIP_UNLESS_BACKEND(GetParam());
  Material glass;
  glass.color = dvec3(1.0, 0.2, 0.2);
  glass.alpha = 0.0;
  glass.transmission = 1.0;
  const Scene scene = staged(make_box({-0.5, 0.0, -0.5}, {0.5, 1.0, 0.5}), glass);
  // The oracle: two crossings (the bottom face and a side or the top), red and partial.
  const SceneData host(scene, Memory::host);
  auto reference = test::make_shadow_method("reference", "");
  const ProbeResults exact =
      probe_transmittance(Backend::cpu, host, *reference, ground_points_under(scene));
  for (int light = 0; light < 2; ++light)
    for (size_t i = 0; i < ground_points_under(scene).size(); ++i) {
      EXPECT_GT(answer(exact, i, light).x, 0.8);  // 0.96^2 at normal incidence, less obliquely
      EXPECT_LT(answer(exact, i, light).y, 0.05);
    }
  expect_near_oracle(GetParam(), scene, "dsm", "", 0.02);
  expect_near_oracle(GetParam(), scene, "dsm", "filter=bilinear", 0.02);
  expect_near_oracle(GetParam(), scene, "shadowmap", "", 0.02);
  expect_near_oracle(GetParam(), scene, "auto", "", 0.02);
}

TEST_P(ContactShadows, BlendQuadLyingOnTheGroundCastsItsAlpha) {
  DV_SKIP_UNLESS_BACKEND(GetParam());
  Material blend;
  blend.alpha = 0.5;
  blend.alpha_mode = AlphaMode::blend;
  const Scene scene = staged(make_quad(1.0), blend);
  const SceneData host(scene, Memory::host);
  auto reference = test::make_shadow_method("reference", "");
  const ProbeResults exact =
      probe_transmittance(Backend::cpu, host, *reference, ground_points_under(scene));
  for (int light = 0; light < 2; ++light)
    for (size_t i = 0; i < ground_points_under(scene).size(); ++i)
      EXPECT_NEAR(answer(exact, i, light).x, 0.5, 1e-12);
  expect_near_oracle(GetParam(), scene, "dsm", "", 0.02);
  expect_near_oracle(GetParam(), scene, "dsm", "filter=bilinear", 0.02);
  expect_near_oracle(GetParam(), scene, "auto", "", 0.02);
}

// The gap along each staged light's rays against the receiver bias (receiver_depth) each map
// subtracts at ground points under the model at its default resolution 1024, the faces laid out
// as the maps lay them out (fitted_light_map_faces): 1e-4 of the scene diagonal plus slope x
// reach x texel x tan(theta) (dsm: 3 x 0.5, with its bilinear filter 3 x 1; shadowmap 1.5 x 1.5
// for PCF 2). Models of several proportions; the margin is printed.
TEST(ContactShadows, StagedGroundGapExceedsTheDefaultReceiverBias) {
  struct Model {
    const char* name;
    TriangleMesh mesh;
  };
  const Model models[] = {{"unit cube", make_box({-0.5, 0.0, -0.5}, {0.5, 1.0, 0.5})},
                          {"flat quad", make_quad(1.0)},
                          {"tall box", make_box({-0.5, 0.0, -0.5}, {0.5, 3.0, 0.5})},
                          {"wide slab", make_box({-2.0, 0.0, -1.0}, {2.0, 0.2, 1.0})}};
  struct Bias {
    const char* map;
    double slope, reach;
  };
  const Bias biases[] = {{"dsm", 3.0, 0.5}, {"dsm bilinear", 3.0, 1.0}, {"shadowmap", 1.5, 1.5}};
  const char* light_names[] = {"key", "fill"};
  for (const Model& m : models) {
    const Scene scene = staged(m.mesh, Material{});
    const SceneData data(scene, Memory::host);
    const SceneView& s = data.view();
    Aabb model_box;
    for (const dvec3& p : m.mesh.positions) model_box.extend(p);
    const double model_bottom = model_box.lo.y, radius = 0.5 * glm::length(model_box.extent());
    const double gap = model_bottom - ground_height(scene);
    EXPECT_NEAR(gap, kGroundGapRadii * radius, 1e-12) << m.name;
    for (int light = 0; light < 2; ++light) {
      const LightView& l = data.host_lights()[size_t(light)];
      const ShadowFace face =
          fitted_light_map_faces(l, s.bounds, data.host_object_bounds(), s.diagonal, 1024).at(0);
      for (const Bias& b : biases) {
        double smallest_margin = 1e300;
        for (const dvec3& p : ground_points_under(scene)) {
          FacePoint fp;
          ASSERT_TRUE(project_to_face(face, 1024, p, fp));
          const ShadowReceiver r{p, dvec3(0.0, 1.0, 0.0)};
          const double bias =
              fp.depth - receiver_depth(face, r, fp.depth, 1e-4 * s.diagonal, b.slope, b.reach);
          const dvec3 to_light =
              l.type == LightType::directional ? -l.direction : glm::normalize(l.position - p);
          const double gap_along_ray = (model_bottom - p.y) / to_light.y;
          smallest_margin = std::min(smallest_margin, gap_along_ray / bias);
        }
        std::printf("%s, %s, %s light: gap %.3g (%.2f %% of the radius) / receiver bias >= %.2f\n",
                    m.name, b.map, light_names[light], gap, 100.0 * gap / radius, smallest_margin);
        EXPECT_GT(smallest_margin, 1.2) << m.name << " " << b.map << " " << light_names[light];
      }
    }
  }
}

// The fill's orthographic face leaves the staged ground out of its lateral fit (the ground
// shadows nothing: the model lies on its lit side), so its texels follow the model's bounds,
// while its depth range still holds the ground under the model; an upright wall keeps the face
// as it was, and so does a light from below the ground.
TEST(ContactShadows, DirectionalFaceLeavesOutAPlaneThatShadowsNothing) {
  const Scene scene = staged(make_box({-0.5, 0.0, -0.5}, {0.5, 1.0, 0.5}), Material{});
  const SceneData data(scene, Memory::host);
  const SceneView& s = data.view();
  const LightView& fill = data.host_lights()[1];
  ASSERT_EQ(fill.type, LightType::directional);
  const std::vector<Aabb>& objects = data.host_object_bounds();
  ASSERT_EQ(objects.size(), 2u);
  const Aabb casters = directional_casters(fill, s.bounds, objects);
  EXPECT_EQ(casters.lo, objects[0].lo);
  EXPECT_EQ(casters.hi, objects[0].hi);
  const ShadowFace fitted = fitted_light_map_faces(fill, s.bounds, objects, s.diagonal, 1024)[0];
  const ShadowFace whole = light_map_faces(fill, s.bounds, s.diagonal, 1024)[0];
  EXPECT_NEAR(fitted.texel_size, glm::length(objects[0].extent()) / 1024, 1e-9);
  EXPECT_LT(fitted.texel_size, 0.25 * whole.texel_size);
  for (const dvec3& p : ground_points_under(scene)) {
    FacePoint fp;
    ASSERT_TRUE(project_to_face(fitted, 1024, p, fp));
    EXPECT_GT(fp.depth, 0.0);
    EXPECT_GE(fp.u, 0.0);
    EXPECT_LT(fp.u, 1023.0);
    EXPECT_GE(fp.v, 0.0);
    EXPECT_LT(fp.v, 1023.0);
  }
  // Light from below: the model is not on the ground's lit side.
  LightView below = fill;
  below.direction.y = -below.direction.y;
  EXPECT_EQ(directional_casters(below, s.bounds, objects).lo, s.bounds.lo);
  // An upright wall beside the model is flat along x but the model is on both of its sides.
  std::vector<Aabb> with_wall = objects;
  with_wall.push_back(Aabb{dvec3(0.0, 0.0, -2.0), dvec3(0.0, 2.0, 2.0)});
  Aabb all = s.bounds;
  all.extend(with_wall.back());
  const Aabb kept = directional_casters(fill, all, with_wall);
  EXPECT_EQ(kept.hi.y, 2.0);
  EXPECT_EQ(kept.lo.y, objects[0].lo.y);
}

// Outside the fill's fitted face the ground is lit, as in the oracle (nothing above it casts
// there), and the cube's long fill shadow on the ground, away from the light, still falls
// inside the face: dsm and shadowmap answer the oracle's 1 at the ground's corners and its 0
// in that shadow.
TEST(ContactShadows, FittedFillFaceKeepsTheModelsShadowAndLightsTheGroundAroundIt) {
  const Scene scene = staged(make_box({-0.5, 0.0, -0.5}, {0.5, 1.0, 0.5}), Material{});
  const SceneData data(scene, Memory::host);
  const LightView& fill = data.host_lights()[1];
  const double y = ground_height(scene);
  // Along the fill's rays from the cube's centre down to the ground: behind the cube.
  const dvec3 centre(0.0, 0.5, 0.0);
  const dvec3 in_shadow = centre + fill.direction * ((y - centre.y) / fill.direction.y);
  const double corner = 2.5;
  const std::vector<dvec3> points = {in_shadow,
                                     {corner, y, corner},
                                     {-corner, y, corner},
                                     {corner, y, -corner},
                                     {-corner, y, -corner}};
  auto reference = test::make_shadow_method("reference", "");
  const ProbeResults exact = probe_transmittance(Backend::cpu, data, *reference, points);
  EXPECT_EQ(answer(exact, 0, 1).x, 0.0);
  for (size_t i = 1; i < points.size(); ++i) EXPECT_EQ(answer(exact, i, 1).x, 1.0) << i;
  for (const char* method : {"dsm", "shadowmap"}) {
    auto m = test::make_shadow_method(method, "");
    const ProbeResults r = probe_transmittance(Backend::cpu, data, *m, points);
    for (size_t i = 0; i < points.size(); ++i)
      EXPECT_NEAR(answer(r, i, 1).x, answer(exact, i, 1).x, 1e-6) << method << " point " << i;
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, ContactShadows, ::testing::ValuesIn(test::all_backends()),
                         [](const ::testing::TestParamInfo<Backend>& info) {
                           return std::string(info.param == Backend::cuda ? "cuda" : "cpu");
                         });

}  // namespace
}  // namespace dv
