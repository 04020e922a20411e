// The seeds scenes (experiments/scenes/seeds/, written by make_seed_scenes.py): every file loads,
// and each stand-in has the properties of the paper setup it stands in for (triangle counts of
// Buchacher's models, one volume plus six polygonal objects in Knecht's X-ray scene at the
// table's three dataset resolutions, N steaming cups, a spot plus an omni light in Fig. 5.4,
// Knecht's 720 x 480 and Hadwiger's 512 x 512 images).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "experiments/source_paths.h"
#include "render/load/scene_loader.h"

namespace dv::test {
namespace {

namespace fs = std::filesystem;

std::string seeds_dir() {
  return source_dir() + "/experiments/scenes/seeds";
}

std::vector<std::string> seed_scene_files() {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(seeds_dir()))
    if (entry.path().extension() == ".json") names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

Scene seed(const std::string& name) {
  return load_scene(seeds_dir() + "/" + name);
}

int64_t triangles(const Scene& scene, const Object& object) {
  return int64_t(scene.meshes[object.mesh].triangles.size());
}

int count_objects(const Scene& scene, InteriorKind kind) {
  return int(std::count_if(scene.objects.begin(), scene.objects.end(),
                           [&](const Object& o) { return o.interior.kind == kind; }));
}

class SeedScene : public testing::TestWithParam<std::string> {};

TEST_P(SeedScene, LoadsWithALightAndTheTablesImageSize) {
  const Scene scene = seed(GetParam());
  EXPECT_FALSE(scene.lights.empty());
  EXPECT_FALSE(scene.objects.empty());
  if (GetParam().rfind("knecht-", 0) == 0) {  // Knecht 2011 renders everything at 720 x 480
    EXPECT_EQ(scene.camera.width, 720);
    EXPECT_EQ(scene.camera.height, 480);
  }
}

INSTANTIATE_TEST_SUITE_P(Seeds, SeedScene, testing::ValuesIn(seed_scene_files()), SceneFileName());

TEST(SeedScenes, BuchacherModelsHaveTheStatedTriangleCounts) {
  const std::pair<const char*, int64_t> models[] = {{"buchacher-simple-quad.json", 2},
                                                    {"buchacher-complex-quad.json", 11858},
                                                    {"buchacher-cube.json", 12},
                                                    {"buchacher-bunny.json", 58784},
                                                    {"buchacher-buddha-standin.json", 940544}};
  for (const auto& [file, count] : models) {
    const Scene scene = seed(file);
    ASSERT_EQ(scene.objects.size(), 1u) << file;
    EXPECT_EQ(triangles(scene, scene.objects[0]), count) << file;
  }
}

TEST(SeedScenes, BuchacherQuadsFaceTheDepthAxisAndTheCubeIsAxisParallel) {
  for (const char* file : {"buchacher-simple-quad.json", "buchacher-complex-quad.json"}) {
    const Aabb box = world_bounds(seed(file));
    EXPECT_EQ(box.lo.z, 0.0) << file;  // exactly in z = 0: no tilt from a rotation
    EXPECT_EQ(box.hi.z, 0.0) << file;
    EXPECT_EQ(box.hi.x - box.lo.x, 1.0) << file;
    EXPECT_EQ(box.hi.y - box.lo.y, 1.0) << file;
  }
  const Aabb cube = world_bounds(seed("buchacher-cube.json"));
  EXPECT_EQ(cube.lo, dvec3(-0.5));
  EXPECT_EQ(cube.hi, dvec3(0.5));
}

TEST(SeedScenes, XrayHasOneVolumeAndSixPolygonalObjectsAtEachDatasetResolution) {
  const std::pair<const char*, ivec3> files[] = {
      {"knecht-fig510-xray-512x512x96.json", {512, 512, 96}},
      {"knecht-fig510-xray-256x256x48.json", {256, 256, 48}},
      {"knecht-fig510-xray-128x128x24.json", {128, 128, 24}},
      {"knecht-fig511-eps.json", {256, 256, 48}}};
  Aabb first_extent;
  bool first = true;
  for (const auto& [file, dims] : files) {
    const Scene scene = seed(file);
    EXPECT_EQ(count_objects(scene, InteriorKind::volume), 1) << file;
    EXPECT_EQ(scene.objects.size(), 7u) << file;
    ASSERT_EQ(scene.volumes.size(), 1u) << file;
    EXPECT_EQ(scene.volumes[0].dims, dims) << file;
    const Aabb extent = scene.volumes[0].bounds();
    if (first) first_extent = extent;
    first = false;
    for (int axis = 0; axis < 3; ++axis) {  // the same phantom size at every resolution
      EXPECT_NEAR(extent.lo[axis], first_extent.lo[axis], 1e-6) << file;
      EXPECT_NEAR(extent.hi[axis], first_extent.hi[axis], 1e-6) << file;
    }
  }
}

TEST(SeedScenes, CupScenesHoldNSteamingCupsUnderTheSameCameraAndLight) {
  const Scene one = seed("knecht-fig512-cups-1.json");
  for (int n : {1, 2, 4, 8, 12, 16, 20, 24}) {
    const std::string file = "knecht-fig512-cups-" + std::to_string(n) + ".json";
    const Scene scene = seed(file);
    int cups = 0;
    for (const Object& o : scene.objects) cups += o.name.rfind("cup-", 0) == 0;
    EXPECT_EQ(cups, n) << file;
    EXPECT_EQ(count_objects(scene, InteriorKind::volume), n) << file;
    EXPECT_EQ(scene.objects.size(), size_t(2 * n + 1)) << file;  // plus the floor
    EXPECT_EQ(scene.camera.position, one.camera.position) << file;
    ASSERT_EQ(scene.lights.size(), 1u) << file;
    EXPECT_EQ(scene.lights[0].position, one.lights[0].position) << file;
  }
}

TEST(SeedScenes, TeapotSceneHasASpotAndAnOmniLight) {
  const Scene scene = seed("knecht-fig514-d-teapot-teacup.json");
  ASSERT_EQ(scene.lights.size(), 2u);
  EXPECT_EQ(scene.lights[0].type, LightType::spot);
  EXPECT_EQ(scene.lights[1].type, LightType::omni);
}

TEST(SeedScenes, HadwigerSceneIsVolumeOnlyAt512) {
  const Scene scene = seed("hadwiger-fig4-ct-volume.json");
  EXPECT_EQ(count_objects(scene, InteriorKind::volume), int(scene.objects.size()));
  EXPECT_EQ(scene.camera.width, 512);
  EXPECT_EQ(scene.camera.height, 512);
}

}  // namespace
}  // namespace dv::test
