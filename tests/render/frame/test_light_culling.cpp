// Light culling per screen tile (engine/raster/light_tiles.h): the ball test never drops a light
// that adds to a point of the ball; with cut-off 0 a culled frame has the bits of an unculled
// one (raster and ray-walk renderers, CPU and CUDA) while its pixels evaluate fewer lights; with
// a cut-off the change stays within the stated bound and more lights are dropped; the camera
// pass's two light loops (plain, and over listed lights) give a one-light frame the same bits.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "cuda/device_memory.h"
#include "experiments/source_paths.h"
#include "render/frame/raster_render.h"
#include "render/frame/shading.h"
#include "render/load/scene_loader.h"
#include "strategies/shadow/shadow_method.h"

namespace dv {
namespace {

LightView random_light(std::mt19937& rng, LightType type) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  LightView l{};
  l.type = type;
  l.position = dvec3(u(rng), u(rng), u(rng)) * 3.0;
  l.direction = glm::normalize(dvec3(u(rng), u(rng), u(rng)) + dvec3(0.0, 0.0, 1e-3));
  const double cutoff_deg = 5.0 + 80.0 * (0.5 + 0.5 * u(rng));
  l.cos_cutoff = std::cos(cutoff_deg * 3.14159265358979323846 / 180.0);
  l.cos_inner = l.cos_cutoff;
  l.color = dvec3(1.0, 0.5 + 0.5 * u(rng), 0.5);
  l.intensity = 2.0 + u(rng);
  l.range = u(rng) > 0.5 ? 2.0 + u(rng) : 0.0;
  return l;
}

// Light culling drops a light from a ball only when no point of the ball receives more than the
// cut-off from it (nothing at all for cut-off 0): checked at points sampled in each dropped ball.
TEST(LightCulling, TheBallTestDropsOnlyLightsThatAddNothingThere) {
  std::mt19937 rng(52);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int dropped = 0, kept = 0;
  for (const double cutoff : {0.0, 0.05}) {
    for (int trial = 0; trial < 4000; ++trial) {
      const LightView l = random_light(rng, trial % 2 ? LightType::spot : LightType::omni);
      const dvec3 centre = dvec3(u(rng), u(rng), u(rng)) * 5.0;
      const double radius = 0.05 + 1.5 * (0.5 + 0.5 * u(rng));
      if (light_may_reach_ball(l, light_reach(l, cutoff), centre, radius)) {
        ++kept;
        continue;
      }
      ++dropped;
      for (int k = 0; k < 200; ++k) {
        dvec3 d(u(rng), u(rng), u(rng));
        if (glm::length(d) > 1.0) continue;
        // Points on the ball's surface too, where the test is tightest.
        if (k % 4 == 0 && glm::length(d) > 0.0) d = glm::normalize(d);
        const dvec3 p = centre + radius * d;
        const LightArrival a = light_arrival(l, p);
        const double irradiance = a.intensity * std::max({l.color.x, l.color.y, l.color.z});
        if (cutoff == 0.0)
          ASSERT_LE(a.intensity, 0.0) << "trial " << trial << ": a dropped light lights a point";
        else
          ASSERT_LT(irradiance, cutoff) << "trial " << trial;
      }
    }
  }
  EXPECT_GT(dropped, 1000) << "the test exercises the dropping side";
  EXPECT_GT(kept, 1000);
}

TEST(LightCulling, AnInvalidCutoffIsAnError) {
  Scene scene = load_scene(test::source_dir() + "/experiments/scenes/knecht-32-lights.json");
  const SceneData data(scene, Memory::host);
  for (const double bad : {-0.1, std::nan("")})
    EXPECT_THROW(build_light_tiles(Backend::cpu, data.view(), scene.camera, {true, bad}), Error);
}

struct Frames {
  RenderResult culled;
  RenderResult unculled;
};

Frames render_both(Backend backend, bool raster, const Scene& scene, const SceneData& data,
                   ShadowMethod& method, double cutoff) {
  const auto frame = [&](const LightCulling& culling) {
    if (raster)
      return render_raster(backend, data, scene.camera, method, scene.background, {}, culling)
          .render;
    return render_reference(backend, data, scene.camera, method, scene.background, {}, culling);
  };
  Frames f;
  f.culled = frame({true, cutoff});
  f.unculled = frame({false, 0.0});
  return f;
}

double listed_mean(const RenderResult& r) {
  return double(r.counters.listed_lights) / (double(r.image.width) * r.image.height);
}

// knecht-32-lights (16 spot lights, 16 omni lights without range): with cut-off 0 the spot
// lights leave the tiles outside their cones and nothing else changes.
// Maps of 64^2 keep the CPU's 112 faces quick.
void check_exact_culling(Backend backend, bool raster, const std::string& shadows) {
  SCOPED_TRACE(std::string(raster ? "raster" : "ray walk") + ", " + shadows);
  Scene scene = load_scene(test::source_dir() + "/experiments/scenes/knecht-32-lights.json");
  scene.camera.width = 240;
  scene.camera.height = 160;
  const SceneData data(scene, backend == Backend::cuda ? Memory::device : Memory::host);
  auto method = shadow_registry().create(
      shadows, StrategyParams::parse(shadows == "none" ? std::vector<std::string>{}
                                                       : std::vector<std::string>{"res=64"}));
  const Frames f = render_both(backend, raster, scene, data, *method, 0.0);
  ASSERT_TRUE(f.culled.light_culling.enabled);
  ASSERT_FALSE(f.unculled.light_culling.enabled);
  ASSERT_EQ(f.culled.image.rgb.size(), f.unculled.image.rgb.size());
  size_t differing = 0;
  for (size_t i = 0; i < f.culled.image.rgb.size(); ++i)
    differing += f.culled.image.rgb[i] != f.unculled.image.rgb[i];
  EXPECT_EQ(differing, 0u) << "of " << f.culled.image.rgb.size() << " channel values";
  EXPECT_EQ(f.culled.counters.hits, f.unculled.counters.hits);
  EXPECT_EQ(f.culled.counters.volume_samples, f.unculled.counters.volume_samples);
  EXPECT_DOUBLE_EQ(listed_mean(f.unculled), 32.0);
  EXPECT_EQ(f.unculled.counters.max_listed_lights, 32u);
  EXPECT_GE(listed_mean(f.culled), 16.0) << "omni lights without range are never dropped";
  EXPECT_LT(listed_mean(f.culled), 29.0) << "spot lights leave the tiles outside their cones";
}

// With a cut-off, a pixel changes by less than the dropped lights' cut-off times the brightest
// material's diffuse + specular, and its tile lists fewer lights than with cut-off 0.
void check_cutoff(Backend backend) {
  Scene scene = load_scene(test::source_dir() + "/experiments/scenes/knecht-32-lights.json");
  scene.camera.width = 120;
  scene.camera.height = 80;
  const SceneData data(scene, backend == Backend::cuda ? Memory::device : Memory::host);
  auto method = shadow_registry().create("shadowmap", StrategyParams::parse({"res=64"}));
  const double cutoff = 0.06;
  const Frames f = render_both(backend, true, scene, data, *method, cutoff);
  const RenderResult exact =
      render_raster(backend, data, scene.camera, *method, scene.background, {}, {true, 0.0}).render;
  double brightest = 0.0;
  for (const Object& o : scene.objects)
    brightest = std::max(brightest, o.material.diffuse + o.material.specular);
  const double bound = 32.0 * cutoff * brightest;
  double worst = 0.0;
  for (size_t i = 0; i < f.culled.image.rgb.size(); ++i)
    worst = std::max(worst, double(std::abs(f.culled.image.rgb[i] - f.unculled.image.rgb[i])));
  EXPECT_LE(worst, bound);
  EXPECT_GT(worst, 0.0) << "the cut-off drops lights that add something";
  EXPECT_LT(listed_mean(f.culled), listed_mean(exact)) << "omni lights drop beyond their reach";
}

// A one-light frame runs the camera pass's plain loop over every light (no masks); a cut-off so
// small that the light stays listed everywhere gives it masks, and so the loop over listed
// lights (render/frame/shading.h). Both loops must give the same bits.
void check_one_light_loops(Backend backend, const std::string& shadows) {
  SCOPED_TRACE(shadows);
  Scene scene = load_scene(test::source_dir() + "/experiments/scenes/knecht-fig56.json");
  ASSERT_EQ(scene.lights.size(), 1u);
  scene.camera.width = 240;
  scene.camera.height = 160;
  const SceneData data(scene, backend == Backend::cuda ? Memory::device : Memory::host);
  auto method = shadow_registry().create(
      shadows, StrategyParams::parse(shadows == "none" ? std::vector<std::string>{}
                                                       : std::vector<std::string>{"res=256"}));
  const Frames f = render_both(backend, true, scene, data, *method, 1e-300);
  const RenderResult plain =
      render_raster(backend, data, scene.camera, *method, scene.background, {}, {true, 0.0}).render;
  ASSERT_EQ(f.culled.image.rgb.size(), plain.image.rgb.size());
  EXPECT_EQ(f.culled.counters.max_listed_lights, 1u);
  EXPECT_GT(listed_mean(f.culled), 0.5) << "the light is listed wherever something is shaded";
  size_t differing = 0;
  for (size_t i = 0; i < plain.image.rgb.size(); ++i)
    differing += f.culled.image.rgb[i] != plain.image.rgb[i] ||
                 f.unculled.image.rgb[i] != plain.image.rgb[i];
  EXPECT_EQ(differing, 0u) << "of " << plain.image.rgb.size() << " channel values";
}

TEST(LightCulling, CpuPlainAndListedLoopsAgree) {
  for (const std::string shadows : {"none", "shadowmap", "dsm"})
    check_one_light_loops(Backend::cpu, shadows);
}

TEST(LightCulling, CudaPlainAndListedLoopsAgree) {
  std::string why;
  if (!cuda_device_available(&why)) GTEST_SKIP() << "needs a GPU: " << why;
  for (const std::string shadows : {"none", "shadowmap", "dsm"})
    check_one_light_loops(Backend::cuda, shadows);
}

TEST(LightCulling, CpuExactCullingKeepsTheBits) {
  for (const bool raster : {true, false}) check_exact_culling(Backend::cpu, raster, "none");
  check_exact_culling(Backend::cpu, true, "shadowmap");
  check_exact_culling(Backend::cpu, true, "dsm");
}

TEST(LightCulling, CpuCutoffStaysWithinItsBound) {
  check_cutoff(Backend::cpu);
}

TEST(LightCulling, CudaExactCullingKeepsTheBits) {
  std::string why;
  if (!cuda_device_available(&why)) GTEST_SKIP() << "needs a GPU: " << why;
  for (const bool raster : {true, false}) check_exact_culling(Backend::cuda, raster, "none");
  check_exact_culling(Backend::cuda, true, "shadowmap");
  check_exact_culling(Backend::cuda, true, "dsm");
}

TEST(LightCulling, CudaCutoffStaysWithinItsBound) {
  std::string why;
  if (!cuda_device_available(&why)) GTEST_SKIP() << "needs a GPU: " << why;
  check_cutoff(Backend::cuda);
}

}  // namespace
}  // namespace dv
