// CPU/CUDA parity of the shared code: oracle answers, reference (ray-walk) renders and
// rasterized renders on scenes with translucent surfaces, constant media, volumes and many
// objects, and on the textured stand-ins (texture alpha, base colour, vertex normals; also
// every shadow method's answers there). Tolerance: the backends run the
// same double-precision code without FMA contraction; exp/pow/cos of the two math libraries
// differ by an ulp or so, so transmittances agree to 1e-12 and 8-bit-relevant image values to
// 1e-6 (float output), and integer counters exactly. Skipped, with the reason, without a GPU.
#include <gtest/gtest.h>

#include <random>

#include "cuda/device_memory.h"
#include "experiments/source_paths.h"
#include "render/frame/raster_render.h"
#include "render/frame/reference_render.h"
#include "render/load/scene_loader.h"
#include "strategies/shadow/probe.h"

namespace dv {
namespace {

class Parity : public ::testing::TestWithParam<const char*> {
 protected:
  void SetUp() override {
    std::string why;
    if (!cuda_device_available(&why)) GTEST_SKIP() << "CPU/CUDA parity needs a GPU: " << why;
  }
};

// Scenes under experiments/scenes/, glTF stand-ins under tests/data/textured/.
std::string scene_path(const std::string& name) {
  const bool gltf = name.find(".gl") != std::string::npos;
  return test::source_dir() + (gltf ? "/tests/data/textured/" : "/experiments/scenes/") + name;
}

TEST_P(Parity, OracleAndRenderAgree) {
  Scene scene = load_scene(scene_path(GetParam()));
  scene.camera.width = 96;
  scene.camera.height = 72;
  const SceneData host(scene, Memory::host), device(scene, Memory::device);
  const Aabb b = world_bounds(scene);
  std::mt19937 rng(3);
  std::vector<dvec3> points;
  for (int i = 0; i < 2000; ++i) {
    dvec3 p;
    for (int a = 0; a < 3; ++a)
      p[a] = std::uniform_real_distribution<double>(b.lo[a], b.hi[a])(rng);
    points.push_back(p);
  }
  auto reference = shadow_registry().create("reference");
  const ProbeResults c = probe_transmittance(Backend::cpu, host, *reference, points);
  const ProbeResults g = probe_transmittance(Backend::cuda, device, *reference, points);
  ASSERT_EQ(c.transmittance.size(), g.transmittance.size());
  for (size_t i = 0; i < c.transmittance.size(); ++i) {
    EXPECT_NEAR(c.transmittance[i], g.transmittance[i], 1e-12) << i;
    EXPECT_EQ(c.flags[i], g.flags[i]) << i;
  }
  const RenderResult rc =
      render_reference(Backend::cpu, host, scene.camera, *reference, scene.background);
  const RenderResult rg =
      render_reference(Backend::cuda, device, scene.camera, *reference, scene.background);
  ASSERT_EQ(rc.image.rgb.size(), rg.image.rgb.size());
  double worst = 0.0;
  for (size_t i = 0; i < rc.image.rgb.size(); ++i)
    worst = std::max(worst, double(std::abs(rc.image.rgb[i] - rg.image.rgb[i])));
  EXPECT_LE(worst, 1e-6);
  EXPECT_EQ(rc.counters.hits, rg.counters.hits);
  EXPECT_EQ(rc.counters.volume_samples, rg.counters.volume_samples);
  EXPECT_EQ(rc.counters.max_hits, rg.counters.max_hits);
  EXPECT_EQ(rc.counters.overflow_pixels, rg.counters.overflow_pixels);
  // The rasterizing renderer: identical tile lists (integer coverage), images as above.
  const RasterRenderResult xc =
      render_raster(Backend::cpu, host, scene.camera, *reference, scene.background);
  const RasterRenderResult xg =
      render_raster(Backend::cuda, device, scene.camera, *reference, scene.background);
  EXPECT_EQ(xc.raster.entries, xg.raster.entries);
  EXPECT_EQ(xc.raster.pieces, xg.raster.pieces);
  EXPECT_EQ(xc.raster.max_entries_per_tile, xg.raster.max_entries_per_tile);
  EXPECT_EQ(xc.render.counters.hits, xg.render.counters.hits);
  EXPECT_EQ(xc.render.counters.volume_samples, xg.render.counters.volume_samples);
  worst = 0.0;
  for (size_t i = 0; i < xc.render.image.rgb.size(); ++i)
    worst = std::max(worst, double(std::abs(xc.render.image.rgb[i] - xg.render.image.rgb[i])));
  EXPECT_LE(worst, 1e-6);
}

INSTANTIATE_TEST_SUITE_P(Scenes, Parity,
                         ::testing::Values("demo.json", "ct-phantom.json",
                                           "intersecting-volumes.json", "translucent-boxes.json",
                                           "many-objects.json"),
                         test::SceneFileName());
INSTANTIATE_TEST_SUITE_P(Textured, Parity,
                         ::testing::Values("alpha_mask_quad.gltf", "textured_sphere.glb"),
                         test::SceneFileName());

// Texture alpha in every shadow method's maps (depth maps, deep shadow maps, slicemap grids):
// the backends give the same answers on a grid of floor points of the cut-out stand-in.
TEST(TexturedParity, ShadowMethodsAgree) {
  std::string why;
  if (!cuda_device_available(&why)) GTEST_SKIP() << "CPU/CUDA parity needs a GPU: " << why;
  const Scene scene = load_scene(scene_path("alpha_mask_quad.gltf"));
  const SceneData host(scene, Memory::host), device(scene, Memory::device);
  std::vector<dvec3> points;
  for (int i = 0; i < 40; ++i)
    for (int k = 0; k < 10; ++k) points.push_back({-2.0 + 0.1 * i, 0.0, -0.5 + 0.1 * k});
  for (const char* name : {"shadowmap", "dsm", "transmittance-slicemap", "auto"}) {
    SCOPED_TRACE(name);
    auto on_cpu = shadow_registry().create(name), on_gpu = shadow_registry().create(name);
    const ProbeResults c = probe_transmittance(Backend::cpu, host, *on_cpu, points);
    const ProbeResults g = probe_transmittance(Backend::cuda, device, *on_gpu, points);
    for (size_t i = 0; i < c.transmittance.size(); ++i)
      EXPECT_NEAR(c.transmittance[i], g.transmittance[i], 1e-12) << i;
  }
}

}  // namespace
}  // namespace dv
