// The camera pass's kernel for plain surface looks (render/frame/shade_payload.h): a grey scene
// (every surface untextured, without glass, not emitting) runs it when the pass has no light
// lists, and it gives the bits of the general kernel with each shadow source on the CPU and on
// CUDA; a scene with glass or textures, a material that emits, and a pass with light lists run
// the general kernel.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "cuda/device_memory.h"
#include "experiments/source_paths.h"
#include "render/frame/raster_render.h"
#include "render/frame/shade_payload.h"
#include "render/load/scene_loader.h"
#include "strategies/shadow/shadow_method.h"

namespace dv {
namespace {

std::unique_ptr<ShadowMethod> method_for(const std::string& shadows) {
  return shadow_registry().create(
      shadows, StrategyParams::parse(shadows == "none" ? std::vector<std::string>{}
                                                       : std::vector<std::string>{"res=256"}));
}

Scene small_scene(const std::string& file) {
  Scene scene = load_scene(test::source_dir() + "/experiments/scenes/" + file);
  scene.camera.width = 240;
  scene.camera.height = 160;
  return scene;
}

void check_fitted_bits(Backend backend, const std::string& file, const std::string& shadows) {
  SCOPED_TRACE(file + ", " + shadows);
  const Scene scene = small_scene(file);
  const SceneData data(scene, backend == Backend::cuda ? Memory::device : Memory::host);
  const auto method = method_for(shadows);
  const RasterRenderResult fitted =
      render_raster(backend, data, scene.camera, *method, scene.background);
  const RasterRenderResult general = render_raster(backend, data, scene.camera, *method,
                                                   scene.background, {}, {}, LooksKernel::general);
  EXPECT_TRUE(fitted.plain_looks_pass) << "a grey scene with one light runs the fitted kernel";
  EXPECT_FALSE(general.plain_looks_pass);
  ASSERT_EQ(fitted.render.image.rgb.size(), general.render.image.rgb.size());
  size_t differing = 0, lit = 0;
  for (size_t i = 0; i < general.render.image.rgb.size(); ++i) {
    differing += fitted.render.image.rgb[i] != general.render.image.rgb[i];
    lit += general.render.image.rgb[i] != float(scene.background[int(i % 3)]);
  }
  EXPECT_EQ(differing, 0u) << "of " << general.render.image.rgb.size() << " channel values";
  EXPECT_GT(lit, general.render.image.rgb.size() / 10) << "the frame shows the scene";
  EXPECT_EQ(fitted.render.counters.hits, general.render.counters.hits);
  EXPECT_EQ(fitted.render.counters.volume_samples, general.render.counters.volume_samples);
}

void check_every_source(Backend backend) {
  for (const std::string file : {"knecht-fig56.json", "translucent-boxes.json"})
    for (const std::string shadows : {"none", "shadowmap", "dsm"})
      check_fitted_bits(backend, file, shadows);
}

TEST(SurfaceLooks, CpuFittedKernelGivesTheGeneralBits) {
  check_every_source(Backend::cpu);
}

TEST(SurfaceLooks, CudaFittedKernelGivesTheGeneralBits) {
  std::string why;
  if (!cuda_device_available(&why)) GTEST_SKIP() << "needs a GPU: " << why;
  check_every_source(Backend::cuda);
}

TEST(SurfaceLooks, ScenesWithGlassTexturesOrEmissionRunTheGeneralKernel) {
  const auto none = method_for("none");
  for (const std::string file : {"glass-red-slab.json", "../assets/gltf/textured-torus.gltf"}) {
    SCOPED_TRACE(file);
    const Scene scene = small_scene(file);
    const SceneData data(scene, Memory::host);
    EXPECT_FALSE(
        render_raster(Backend::cpu, data, scene.camera, *none, scene.background).plain_looks_pass);
  }
  Scene emitting = small_scene("translucent-boxes.json");
  emitting.objects.back().material.emission = dvec3(0.0, 0.0, 0.25);
  const SceneData data(emitting, Memory::host);
  EXPECT_FALSE(render_raster(Backend::cpu, data, emitting.camera, *none, emitting.background)
                   .plain_looks_pass);
}

TEST(SurfaceLooks, PassesWithLightListsRunTheGeneralKernel) {
  const Scene scene = small_scene("knecht-32-lights.json");
  const SceneData data(scene, Memory::host);
  const auto none = method_for("none");
  const RasterRenderResult culled =
      render_raster(Backend::cpu, data, scene.camera, *none, scene.background);
  EXPECT_GT(culled.render.counters.max_listed_lights, 0u) << "the pass has light lists";
  EXPECT_FALSE(culled.plain_looks_pass);
}

TEST(SurfaceLooks, PlainLookIsUntexturedOpaqueOrBlendedAndDark) {
  ObjectView o{};
  o.texture = -1;
  o.emissive_texture = -1;
  o.alpha = 0.5;
  EXPECT_TRUE(plain_look(o));
  ObjectView glass = o;
  glass.transmission = 0.9;
  ObjectView textured = o;
  textured.texture = 0;
  ObjectView glowing = o;
  glowing.emission = dvec3(0.0, 1e-9, 0.0);
  ObjectView glow_map = o;
  glow_map.emissive_texture = 2;
  for (const ObjectView& looked : {glass, textured, glowing, glow_map})
    EXPECT_FALSE(plain_look(looked));
}

}  // namespace
}  // namespace dv
