// The exact oracle's deferred camera pass (render/frame/oracle_frame.h) gives the bits of the
// direct pass: the same image, counters and oracle flags, on one light and on many (queries
// ordered by light), in one round and in many small ones, in the raster and the ray-walk
// renderer, on the CPU and on CUDA (skipped without a GPU), for volumes, constant media,
// tinted glass and a textured glTF stand-in.
#include <gtest/gtest.h>

#include <string>

#include "cuda/device_memory.h"
#include "experiments/source_paths.h"
#include "render/frame/raster_render.h"
#include "render/load/scene_loader.h"
#include "strategies/shadow/shadow_method.h"

namespace dv {
namespace {

struct Case {
  const char* scene;  // under experiments/scenes/, or a glTF under tests/data/textured/
  int width, height;
};

std::string scene_path(const std::string& name) {
  const bool gltf = name.find(".gl") != std::string::npos;
  return test::source_dir() + (gltf ? "/tests/data/textured/" : "/experiments/scenes/") + name;
}

void expect_same_bits(const RenderResult& direct, const RenderResult& deferred) {
  ASSERT_FALSE(direct.oracle.deferred());
  ASSERT_TRUE(deferred.oracle.deferred());
  ASSERT_EQ(direct.image.rgb.size(), deferred.image.rgb.size());
  size_t differing = 0;
  for (size_t i = 0; i < direct.image.rgb.size(); ++i)
    differing += direct.image.rgb[i] != deferred.image.rgb[i];
  EXPECT_EQ(differing, 0u) << "of " << direct.image.rgb.size() << " channel values";
  const RenderCounters& a = direct.counters;
  const RenderCounters& b = deferred.counters;
  EXPECT_EQ(a.hits, b.hits);
  EXPECT_EQ(a.volume_samples, b.volume_samples);
  EXPECT_EQ(a.max_hits, b.max_hits);
  EXPECT_EQ(a.overflow_pixels, b.overflow_pixels);
  EXPECT_EQ(a.oracle_flag_pixels, b.oracle_flag_pixels);
  EXPECT_EQ(a.listed_lights, b.listed_lights);
  EXPECT_EQ(a.max_listed_lights, b.max_listed_lights);
}

// Renders the case's frame with the oracle's shadows, direct or with `options`: the raster
// renderer's frame, or the ray-walk reference renderer's.
using Renderer = RenderResult (*)(Backend, const SceneData&, const Camera&, ShadowMethod&,
                                  const dvec3&, const OracleFrameOptions&);

RenderResult raster_frame(Backend backend, const SceneData& data, const Camera& camera,
                          ShadowMethod& oracle, const dvec3& background,
                          const OracleFrameOptions& options) {
  return render_raster(backend, data, camera, oracle, background, options).render;
}

RenderResult reference_frame(Backend backend, const SceneData& data, const Camera& camera,
                             ShadowMethod& oracle, const dvec3& background,
                             const OracleFrameOptions& options) {
  return render_reference(backend, data, camera, oracle, background, options);
}

void check_case(Backend backend, const Case& c, Renderer render) {
  Scene scene = load_scene(scene_path(c.scene));
  scene.camera.width = c.width;
  scene.camera.height = c.height;
  const SceneData data(scene, backend == Backend::cuda ? Memory::device : Memory::host);
  auto oracle = shadow_registry().create("reference");
  OracleFrameOptions direct_options;
  direct_options.deferred = false;
  const RenderResult direct =
      render(backend, data, scene.camera, *oracle, scene.background, direct_options);
  const RenderResult deferred = render(backend, data, scene.camera, *oracle, scene.background, {});
  SCOPED_TRACE(std::string(c.scene) + ", one round");
  expect_same_bits(direct, deferred);
  EXPECT_EQ(deferred.oracle.rounds, 1);
  EXPECT_GT(deferred.oracle.queries, int64_t(c.width) * c.height / 4)
      << "most pixels shade a lit surface or volume";

  OracleFrameOptions small_rounds;
  small_rounds.queries_per_round = deferred.oracle.queries / 7 + 1;
  const RenderResult rounds =
      render(backend, data, scene.camera, *oracle, scene.background, small_rounds);
  SCOPED_TRACE("rounds of at most " + std::to_string(small_rounds.queries_per_round) +
               " queries (a round holds at least 32 threads)");
  expect_same_bits(direct, rounds);
  EXPECT_GE(rounds.oracle.rounds, 2);
  EXPECT_EQ(rounds.oracle.queries, deferred.oracle.queries);
}

const Case kCases[] = {
    {"knecht-fig56.json", 72, 48},         // smoke and translucent boxes, one spot light
    {"knecht-32-lights.json", 36, 24},     // 16 spot and 16 omni lights: queries by light
    {"glass-tinted-medium.json", 48, 32},  // tinted glass around a constant medium
    {"textured_sphere.glb", 40, 40},       // a textured glTF stand-in
};

TEST(DeferredOracle, CpuGivesTheBitsOfTheDirectPass) {
  for (const Case& c : kCases) check_case(Backend::cpu, c, raster_frame);
}

TEST(DeferredOracle, CpuReferenceRendererGivesTheBitsOfTheDirectPass) {
  for (const Case& c : kCases) check_case(Backend::cpu, c, reference_frame);
}

TEST(DeferredOracle, CudaGivesTheBitsOfTheDirectPass) {
  std::string why;
  if (!cuda_device_available(&why)) GTEST_SKIP() << "needs a GPU: " << why;
  for (const Case& c : kCases) check_case(Backend::cuda, c, raster_frame);
}

TEST(DeferredOracle, CudaReferenceRendererGivesTheBitsOfTheDirectPass) {
  std::string why;
  if (!cuda_device_available(&why)) GTEST_SKIP() << "needs a GPU: " << why;
  for (const Case& c : kCases) check_case(Backend::cuda, c, reference_frame);
}

TEST(DeferredOracle, RejectsAnEmptyRound) {
  Scene scene = load_scene(scene_path("knecht-fig56.json"));
  scene.camera.width = 8;
  scene.camera.height = 8;
  const SceneData data(scene, Memory::host);
  auto oracle = shadow_registry().create("reference");
  OracleFrameOptions options;
  options.queries_per_round = 0;
  EXPECT_THROW(render_raster(Backend::cpu, data, scene.camera, *oracle, scene.background, options),
               Error);
}

}  // namespace
}  // namespace dv
