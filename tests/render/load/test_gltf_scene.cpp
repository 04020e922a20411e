// glTF import: geometry under composed node transforms, strips and fans, instancing, cameras,
// punctual lights and the defaults used when a file has no camera or light; .gltf with a data
// URI, with an external .bin, and .glb.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "core/log.h"
#include "engine/scene/default_staging.h"
#include "engine/scene/mesh_topology.h"
#include "render/load/gltf_import.h"
#include "render/load/scene_loader.h"
#include "tests/render/load/gltf_builder.h"

namespace dv {
namespace {

using test::GltfBuilder;
using test::json;
using test::ScratchDir;

constexpr double kPi = 3.14159265358979323846;
const double kHalf = std::sqrt(0.5);

void expect_near(const dvec3& got, const dvec3& want, double tol = 1e-9) {
  EXPECT_NEAR(got.x, want.x, tol);
  EXPECT_NEAR(got.y, want.y, tol);
  EXPECT_NEAR(got.z, want.z, tol);
}

dvec3 world(const Object& obj, const dvec3& p) {
  return dvec3(obj.transform * dvec4(p, 1.0));
}

// Parent: translation (1,2,3), 90 degrees about +Y, scale (2,1,0.5); child: matrix that
// translates by (0,0,1). A vertex p lands at (1 + 0.5 (p.z + 1), 2 + p.y, 3 - 2 p.x).
GltfBuilder transformed_box() {
  GltfBuilder b;
  int mesh = test::add_box_mesh(b);
  int child = b.add_node(
      {{"mesh", mesh}, {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 1, 1}}}, false);
  b.add_node({{"translation", {1, 2, 3}},
              {"rotation", {0, kHalf, 0, kHalf}},
              {"scale", {2, 1, 0.5}},
              {"children", {child}}});
  return b;
}

void check_transformed_box(const Scene& scene) {
  ASSERT_EQ(scene.objects.size(), 1u);
  ASSERT_EQ(scene.meshes.size(), 1u);
  const TriangleMesh& mesh = scene.meshes[0];
  EXPECT_EQ(mesh.triangles.size(), 12u);
  EXPECT_EQ(mesh.positions.size(), 8u);  // the 24 exported vertices merged at the seams
  EXPECT_TRUE(is_closed(mesh));
  EXPECT_GT(signed_volume(mesh), 0.0);
  for (const dvec3& p : mesh.positions) {
    EXPECT_DOUBLE_EQ(std::abs(p.x), 1.0);  // positions stay in object space
    expect_near(world(scene.objects[0], p), dvec3(1 + 0.5 * (p.z + 1), 2 + p.y, 3 - 2 * p.x));
  }
}

TEST(GltfScene, BoxUnderComposedNodeTransforms) {
  ScratchDir dir;
  GltfBuilder b = transformed_box();
  check_transformed_box(load_gltf_scene(b.write_gltf(dir.file("box.gltf"))));
}

TEST(GltfScene, ExternalBinAndGlbGiveTheSameScene) {
  ScratchDir dir;
  GltfBuilder b = transformed_box();
  check_transformed_box(load_gltf_scene(b.write_gltf_external_bin(dir.file("box.gltf"), "b.bin")));
  test::write_bytes(dir.file("box.glb"), b.glb_bytes());
  Scene scene = load_gltf_scene(dir.file("box.glb"));
  check_transformed_box(scene);
  EXPECT_EQ(scene.source, dir.file("box.glb"));
}

TEST(GltfScene, StripAndFanBecomeTriangles) {
  ScratchDir dir;
  GltfBuilder b;
  int quad = b.add_positions({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0});  // strip order
  int strip = b.add_mesh({{"attributes", {{"POSITION", quad}}}, {"mode", 5}});
  int fan_pos = b.add_positions({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0});  // fan order
  int fan = b.add_mesh({{"attributes", {{"POSITION", fan_pos}}}, {"mode", 6}});
  b.add_node({{"mesh", strip}});
  b.add_node({{"mesh", fan}});
  Scene scene = load_gltf_scene(b.write_gltf(dir.file("sf.gltf")));
  ASSERT_EQ(scene.meshes.size(), 2u);
  for (const TriangleMesh& mesh : scene.meshes) {
    ASSERT_EQ(mesh.triangles.size(), 2u);
    for (const u32vec3& t : mesh.triangles) {  // all counter-clockwise seen from +Z
      dvec3 n = glm::cross(mesh.positions[t[1]] - mesh.positions[t[0]],
                           mesh.positions[t[2]] - mesh.positions[t[0]]);
      EXPECT_NEAR(n.z, 1.0, 1e-12);
    }
  }
}

TEST(GltfScene, InstancesShareOneMesh) {
  ScratchDir dir;
  GltfBuilder b;
  int mesh = test::add_box_mesh(b);
  b.add_node({{"mesh", mesh}, {"name", "left"}, {"translation", {-3, 0, 0}}});
  b.add_node({{"mesh", mesh}, {"name", "right"}, {"translation", {3, 0, 0}}});
  Scene scene = load_gltf_scene(b.write_gltf(dir.file("inst.gltf")));
  ASSERT_EQ(scene.objects.size(), 2u);
  EXPECT_EQ(scene.meshes.size(), 1u);
  EXPECT_EQ(scene.objects[0].name, "left");
  EXPECT_EQ(scene.objects[1].mesh, scene.objects[0].mesh);
  Aabb box = world_bounds(scene);
  expect_near(box.lo, dvec3(-4, -1, -1));
  expect_near(box.hi, dvec3(4, 1, 1));
}

TEST(GltfScene, FirstCameraNodeGivesPositionOrientationAndFov) {
  ScratchDir dir;
  GltfBuilder b;
  b.add_node({{"mesh", test::add_box_mesh(b)}});
  b.doc["cameras"] =
      json::array({{{"type", "perspective"},
                    {"perspective", {{"yfov", 0.5}, {"aspectRatio", 2.0}, {"znear", 0.1}}}},
                   {{"type", "perspective"}, {"perspective", {{"yfov", 1.0}, {"znear", 0.5}}}}});
  // Camera 0 at (10, 1, 0) turned 90 degrees about +Y: it looks along -X at the box.
  b.add_node({{"camera", 0}, {"translation", {10, 1, 0}}, {"rotation", {0, kHalf, 0, kHalf}}});
  b.add_node({{"camera", 1}, {"translation", {0, 0, 7}}});
  Scene scene = load_gltf_scene(b.write_gltf(dir.file("cam.gltf")));
  const Camera& cam = scene.camera;
  expect_near(cam.position, dvec3(10, 1, 0));
  expect_near(glm::normalize(cam.target - cam.position), dvec3(-1, 0, 0));
  expect_near(cam.up, dvec3(0, 1, 0));
  EXPECT_NEAR(cam.fov_deg, 0.5 * 180.0 / kPi, 1e-9);
  EXPECT_EQ(cam.width, 640);
  EXPECT_EQ(cam.height, 320);
  EXPECT_DOUBLE_EQ(cam.near_plane, 0.1);
}

TEST(GltfScene, WithoutCameraOrLightsTheDefaultStagingFramesTheScene) {
  ScratchDir dir;
  GltfBuilder b;
  b.add_node({{"mesh", test::add_box_mesh(b)}, {"translation", {5, 0, 0}}});
  Scene scene = load_gltf_scene(b.write_gltf(dir.file("bare.gltf")));
  expect_near(scene.camera.target, dvec3(5, 0, 0));
  EXPECT_EQ(scene.camera.height, 480);
  // The default staging itself is tested in tests/render/frame/test_appearance.cpp.
  const Camera expected = default_camera(world_bounds(scene));
  expect_near(scene.camera.position, expected.position);
  ASSERT_EQ(scene.lights.size(), 2u);
  EXPECT_EQ(scene.lights[0].type, LightType::spot);
  EXPECT_EQ(scene.lights[1].type, LightType::directional);
  EXPECT_TRUE(scene.lights[0].source_unit.empty());  // deepvox's own units

  GltfImportOptions no_defaults;
  no_defaults.default_lights = false;
  EXPECT_TRUE(load_gltf_scene(dir.file("bare.gltf"), no_defaults).lights.empty());
}

TEST(GltfScene, StagedLightsStandOnTheSideOfTheFilesCamera) {
  ScratchDir dir;
  GltfBuilder b;
  b.add_node({{"mesh", test::add_box_mesh(b)}});
  b.doc["cameras"] =
      json::array({{{"type", "perspective"}, {"perspective", {{"yfov", 0.7}, {"znear", 0.1}}}}});
  // Behind the box (-Z), turned 180 degrees about +Y: it looks along +Z at the box, which the
  // default view (from +Z) would light from the front, its back in the dark.
  b.add_node({{"camera", 0}, {"translation", {0, 1, -6}}, {"rotation", {0, 1, 0, 0}}});
  const Scene scene = load_gltf_scene(b.write_gltf(dir.file("behind.gltf")));
  ASSERT_EQ(scene.lights.size(), 2u);
  const dvec3 centre = world_bounds(scene).center();
  const dvec3 to_key = scene.lights[0].position - centre;
  const dvec3 to_cam = scene.camera.position - centre;
  EXPECT_GT(glm::dot(dvec3(to_key.x, 0, to_key.z), dvec3(to_cam.x, 0, to_cam.z)), 0.0);
  EXPECT_LT(to_key.z, 0.0);                                // behind the box, with the camera
  expect_near(scene.lights[1].direction, dvec3(0, 0, 1));  // the fill along the view
  // load_scene adds the staged ground under it.
  const Scene staged = load_scene(dir.file("behind.gltf"));
  ASSERT_EQ(staged.objects.size(), 2u);
  EXPECT_EQ(staged.objects[1].name, "ground");
  EXPECT_EQ(load_scene(dir.file("behind.gltf"), {.ground = GroundPlane::off}).objects.size(), 1u);
}

TEST(GltfScene, PunctualLightsMapToDeepvoxLights) {
  ScratchDir dir;
  GltfBuilder b;
  b.use_extension("KHR_lights_punctual", true);
  b.add_node({{"mesh", test::add_box_mesh(b)}});
  int spot = b.add_light({{"type", "spot"},
                          {"color", {1.0, 0.5, 0.25}},
                          {"intensity", 40},
                          {"spot", {{"innerConeAngle", 0.3}, {"outerConeAngle", 0.5}}}});
  int point = b.add_light({{"type", "point"}, {"intensity", 7.5}});
  int sun = b.add_light({{"type", "directional"}});
  int default_spot = b.add_light({{"type", "spot"}, {"spot", json::object()}});
  auto light_ext = [](int i) { return json{{"KHR_lights_punctual", {{"light", i}}}}; };
  // -90 degrees about +X turns local -Z into world -Y: the spot shines straight down.
  b.add_node({{"translation", {0, 5, 0}},
              {"rotation", {-kHalf, 0, 0, kHalf}},
              {"extensions", light_ext(spot)}});
  b.add_node({{"translation", {1, 2, 3}}, {"extensions", light_ext(point)}});
  b.add_node({{"rotation", {0, kHalf, 0, kHalf}}, {"extensions", light_ext(sun)}});
  b.add_node({{"extensions", light_ext(default_spot)}});
  int ranged = b.add_light({{"type", "point"}, {"intensity", 683}, {"range", 2.0}});
  b.add_node({{"translation", {0, 0, 4}}, {"extensions", light_ext(ranged)}});
  Scene scene = load_gltf_scene(b.write_gltf(dir.file("lights.gltf")));
  ASSERT_EQ(scene.lights.size(), 5u);
  const Light& s = scene.lights[0];
  EXPECT_EQ(s.type, LightType::spot);
  expect_near(s.position, dvec3(0, 5, 0));
  expect_near(s.direction, dvec3(0, -1, 0));
  EXPECT_NEAR(s.cutoff_deg, 0.5 * 180.0 / kPi, 1e-9);
  EXPECT_NEAR(s.penumbra_deg, 0.2 * 180.0 / kPi, 1e-9);
  expect_near(s.color, dvec3(1.0, 0.5, 0.25));
  // Photometric to radiometric at the spec's 683 lm/W: candela -> W/sr, lux -> W/m^2.
  EXPECT_DOUBLE_EQ(s.intensity, 40.0 / 683.0);
  EXPECT_EQ(s.source_unit, "cd");
  EXPECT_DOUBLE_EQ(s.source_intensity, 40.0);
  EXPECT_TRUE(s.gltf_cone);
  EXPECT_EQ(scene.lights[1].type, LightType::omni);
  expect_near(scene.lights[1].position, dvec3(1, 2, 3));
  EXPECT_DOUBLE_EQ(scene.lights[1].intensity, 7.5 / 683.0);
  EXPECT_FALSE(scene.lights[1].gltf_cone);
  EXPECT_DOUBLE_EQ(scene.lights[1].range, 0.0);
  EXPECT_EQ(scene.lights[2].type, LightType::directional);
  expect_near(scene.lights[2].direction, dvec3(-1, 0, 0));  // -Z turned 90 degrees about +Y
  EXPECT_DOUBLE_EQ(scene.lights[2].intensity, 1.0 / 683.0);
  EXPECT_EQ(scene.lights[2].source_unit, "lx");
  EXPECT_DOUBLE_EQ(scene.lights[4].intensity, 1.0);
  EXPECT_DOUBLE_EQ(scene.lights[4].range, 2.0);
  EXPECT_NEAR(scene.lights[3].cutoff_deg, 45.0, 1e-6);  // outerConeAngle defaults to pi/4
  EXPECT_NEAR(scene.lights[3].penumbra_deg, 45.0, 1e-6);
}

TEST(GltfScene, PointsPrimitiveIsSkippedWithAWarning) {
  ScratchDir dir;
  GltfBuilder b;
  int mesh = test::add_box_mesh(b);
  int cloud = b.add_positions({0, 0, 0, 1, 1, 1});
  b.doc["meshes"][mesh]["primitives"].push_back(
      {{"attributes", {{"POSITION", cloud}}}, {"mode", 0}});
  b.add_node({{"mesh", mesh}});
  int before = warning_count();
  Scene scene = load_gltf_scene(b.write_gltf(dir.file("points.gltf")));
  EXPECT_GT(warning_count(), before);
  ASSERT_EQ(scene.objects.size(), 1u);
  EXPECT_EQ(scene.meshes[0].triangles.size(), 12u);
}

TEST(GltfScene, RecognisesGltfExtensions) {
  EXPECT_TRUE(is_gltf_file("a/b/scene.gltf"));
  EXPECT_TRUE(is_gltf_file("Scene.GLB"));
  EXPECT_FALSE(is_gltf_file("scene.obj"));
  EXPECT_FALSE(is_gltf_file("gltf"));
}

}  // namespace
}  // namespace dv
