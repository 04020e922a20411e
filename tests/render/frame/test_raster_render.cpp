// The rasterizing renderer against the BVH ray walk: the two fragment sources must give the
// same image except at pixels whose centre lies within rounding of a triangle edge (the tile
// rasterizer decides coverage in 1/256-pixel fixed point, the ray test in double precision).
// Includes a camera inside a medium and objects crossing the near plane.
#include <gtest/gtest.h>

#include <cmath>

#include "experiments/source_paths.h"
#include "render/frame/raster_render.h"
#include "render/load/scene_loader.h"
#include "tests/support/scene_builder.h"

namespace dv {
namespace {

struct ImageDifference {
  double differing_fraction;  // pixels with a channel off by more than 1e-4
  double max_difference;
};

ImageDifference compare(const Image& a, const Image& b) {
  int differing = 0;
  double worst = 0.0;
  for (int i = 0; i < a.width * a.height; ++i) {
    double d = 0.0;
    for (int c = 0; c < 3; ++c)
      d = std::max(d, double(std::abs(a.rgb[3 * i + c] - b.rgb[3 * i + c])));
    worst = std::max(worst, d);
    differing += d > 1e-4;
  }
  return {double(differing) / (a.width * a.height), worst};
}

ImageDifference raster_vs_raytrace(const Scene& scene, const char* shadows) {
  const SceneData data(scene, Memory::host);
  auto method = shadow_registry().create(shadows);
  const RasterRenderResult raster =
      render_raster(Backend::cpu, data, scene.camera, *method, scene.background);
  const RenderResult ray =
      render_reference(Backend::cpu, data, scene.camera, *method, scene.background);
  EXPECT_EQ(raster.render.counters.overflow_pixels, 0u);
  EXPECT_FALSE(raster.raster.overflow);
  return compare(raster.render.image, ray.image);
}

class RasterMatchesRaytrace : public ::testing::TestWithParam<const char*> {};

TEST_P(RasterMatchesRaytrace, OnlyEdgePixelsDiffer) {
  Scene scene = load_scene(test::source_dir() + "/experiments/scenes/" + GetParam());
  scene.camera.width = 120;
  scene.camera.height = 80;
  const ImageDifference d = raster_vs_raytrace(scene, "none");
  EXPECT_LT(d.differing_fraction, 0.01) << "max difference " << d.max_difference;
}

INSTANTIATE_TEST_SUITE_P(Scenes, RasterMatchesRaytrace,
                         ::testing::Values("demo.json", "translucent-boxes.json",
                                           "many-objects.json", "intersecting-volumes.json"),
                         test::SceneFileName());

TEST(RasterRender, CameraInsideAMediumAndNearPlaneCrossings) {
  // The camera sits inside an absorbing box whose walls cross the near plane; a floor and a
  // translucent panel lie beyond. Inside-ness must start with the box and the walls behind the
  // near plane must toggle it without being shaded.
  test::SceneBuilder b;
  b.add(make_box({-3, -1, -3}, {3, 2, 3}), 0.3, InteriorKind::constant, 0.2);
  Object& floor = b.add(make_box({-2, -0.6, -2}, {2, -0.5, 2}));
  floor.material.color = {0.9, 0.8, 0.7};
  Object& panel = b.add(make_quad(1.0), 0.5);
  panel.transform = glm::dmat4(1.0, 0, 0, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0.2, 0.3, -1.0, 1.0);
  b.omni({0.5, 1.5, 0.5}).intensity = 4.0;
  b.scene.camera.position = {0.0, 0.5, 2.95};
  b.scene.camera.target = {0.0, 0.0, 0.0};
  b.scene.camera.near_plane = 0.1;
  b.scene.camera.width = 96;
  b.scene.camera.height = 64;
  validate_scene(b.scene);
  const ImageDifference d = raster_vs_raytrace(b.scene, "reference");
  EXPECT_LT(d.differing_fraction, 0.01) << "max difference " << d.max_difference;
}

TEST(RasterRender, EmptySpaceSkippingChangesNothingButTheSampleCount) {
  Scene scene = load_scene(test::source_dir() + "/experiments/scenes/knecht-fig56.json");
  scene.camera.width = 120;
  scene.camera.height = 80;
  const SceneData skipping(scene, Memory::host),
      plain(scene, Memory::host, {.empty_space_skipping = false});
  auto none = shadow_registry().create("none");
  const RasterRenderResult a =
      render_raster(Backend::cpu, skipping, scene.camera, *none, scene.background);
  const RasterRenderResult b =
      render_raster(Backend::cpu, plain, scene.camera, *none, scene.background);
  const ImageDifference d = compare(a.render.image, b.render.image);
  EXPECT_LE(d.max_difference, 1e-6);
  EXPECT_LT(a.render.counters.volume_samples, b.render.counters.volume_samples / 2);
  EXPECT_GT(a.render.counters.volume_samples, 0u);
}

}  // namespace
}  // namespace dv
