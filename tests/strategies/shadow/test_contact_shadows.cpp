// Contact shadows on the staged ground (engine/scene/default_staging.h): a model staged without
// lights rests on a ground kGroundGapRadii below its bounds, so its bottom faces are casters
// between the light and the ground in the exact oracle. A translucent bottom face (a red glass
// cube) or a BLEND layer lying on the ground must shadow the ground in the maps too, which holds
// when the gap is wider than the maps' receiver bias there (engine/raster/light_faces.h,
// receiver_depth): dsm within 0.02 of the oracle per channel at ground points under them, for
// the staged key light (not the fill, see expect_near_oracle), on CPU and CUDA, also with
// dsm's bilinear filter, and shadowmap's glass layer for the cube.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

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

// The staged key light's answer at point i (light 0; the fill is light 1).
const dvec3& answer(const ProbeResults& r, size_t i) {
  return r.rgb[i * size_t(r.light_count)];
}

// Every point's per-channel transmittance of the key light from `method` within `tolerance` of
// the oracle's. Not the fill (directional, 25 degrees above the ground): its orthographic map
// spans the 6-radii ground, whose receiver bias on the ground exceeds the gap, so dsm still
// drops a BLEND layer or a glass bottom face resting on the ground from the fill's shadow.
void expect_near_oracle(Backend backend, const Scene& scene, const std::string& method,
                        const std::string& params, double tolerance) {
  const SceneData data(scene, backend == Backend::cuda ? Memory::device : Memory::host);
  const std::vector<dvec3> points = ground_points_under(scene);
  auto reference = test::make_shadow_method("reference", "");
  const ProbeResults exact = probe_transmittance(backend, data, *reference, points);
  auto m = test::make_shadow_method(method, params);
  const ProbeResults r = probe_transmittance(backend, data, *m, points);
  for (size_t i = 0; i < points.size(); ++i)
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(answer(r, i)[c], answer(exact, i)[c], tolerance)
          << method << " " << params << " point " << i << " channel " << c;
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
  for (size_t i = 0; i < ground_points_under(scene).size(); ++i) {
    EXPECT_GT(answer(exact, i).x, 0.8);  // 0.96^2 at normal incidence, less obliquely
    EXPECT_LT(answer(exact, i).y, 0.05);
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
  for (size_t i = 0; i < ground_points_under(scene).size(); ++i)
    EXPECT_NEAR(answer(exact, i).x, 0.5, 1e-12);
  expect_near_oracle(GetParam(), scene, "dsm", "", 0.02);
  expect_near_oracle(GetParam(), scene, "dsm", "filter=bilinear", 0.02);
  expect_near_oracle(GetParam(), scene, "auto", "", 0.02);
}

// The gap along the key light's rays against the receiver bias (receiver_depth) each map
// subtracts at ground points under the model at its default resolution 1024: 1e-4 of the scene
// diagonal plus slope x reach x texel x tan(theta) (dsm: 3 x 0.5, with its bilinear filter
// 3 x 1; shadowmap 1.5 x 1.5 for PCF 2). Models of several proportions; the margin is printed.
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
  for (const Model& m : models) {
    const Scene scene = staged(m.mesh, Material{});
    const SceneData data(scene, Memory::host);
    const SceneView& s = data.view();
    const LightView& key = s.lights[0];
    const ShadowFace face = light_map_faces(key, s.bounds, s.diagonal, 1024).at(0);
    Aabb model_box;
    for (const dvec3& p : m.mesh.positions) model_box.extend(p);
    const double model_bottom = model_box.lo.y, radius = 0.5 * glm::length(model_box.extent());
    const double gap = model_bottom - ground_height(scene);
    EXPECT_NEAR(gap, kGroundGapRadii * radius, 1e-12) << m.name;
    for (const Bias& b : biases) {
      double smallest_margin = 1e300;
      for (const dvec3& p : ground_points_under(scene)) {
        FacePoint fp;
        ASSERT_TRUE(project_to_face(face, 1024, p, fp));
        const ShadowReceiver r{p, dvec3(0.0, 1.0, 0.0)};
        const double bias =
            fp.depth - receiver_depth(face, r, fp.depth, 1e-4 * s.diagonal, b.slope, b.reach);
        const dvec3 to_light = glm::normalize(key.position - p);
        const double gap_along_ray = (model_bottom - p.y) / to_light.y;
        smallest_margin = std::min(smallest_margin, gap_along_ray / bias);
      }
      std::printf("%s, %s: gap %.3g (%.2f %% of the radius) / receiver bias >= %.2f\n", m.name,
                  b.map, gap, 100.0 * gap / radius, smallest_margin);
      EXPECT_GT(smallest_margin, 1.2) << m.name << " " << b.map;
    }
    // The fill light's (directional) margin for dsm at its default nearest-texel lookup, printed
    // only: the maps fit the fill's face to their own bounds, and its contact shadows under the
    // model are not held to the oracle (expect_near_oracle).
    const LightView& fill = s.lights[1];
    const ShadowFace fill_face = light_map_faces(fill, s.bounds, s.diagonal, 1024).at(0);
    const dvec3 p = ground_points_under(scene)[12];
    FacePoint fp;
    ASSERT_TRUE(project_to_face(fill_face, 1024, p, fp));
    const double bias =
        fp.depth - receiver_depth(fill_face, ShadowReceiver{p, dvec3(0.0, 1.0, 0.0)}, fp.depth,
                                  1e-4 * s.diagonal, 3.0, 0.5);
    const double fill_margin = (model_bottom - p.y) / -fill.direction.y / bias;
    std::printf("%s, dsm, fill light: gap along its ray / receiver bias %.2f\n", m.name,
                fill_margin);
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, ContactShadows, ::testing::ValuesIn(test::all_backends()),
                         [](const ::testing::TestParamInfo<Backend>& info) {
                           return std::string(info.param == Backend::cuda ? "cuda" : "cpu");
                         });

}  // namespace
}  // namespace dv
