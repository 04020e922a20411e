// Glass as a translucent caster and RGB shadows end to end, on the committed stand-ins
// (scripts/make_glass_standins.py): the red glass slab's shadow on the floor is partial and red
// in the reference, and every shadow method at its defaults (shadowmap, dsm with each storage,
// transmittance-slicemap, auto) answers within 0.05 of the reference's luminance, the dsm
// within 0.05 per channel; behind a clear pane, a tinted medium's shadow keeps its colour in
// the dsm. The `beer` storage is the exception in numbers, not in colour: its one Beer-Lambert
// curve between the first and the last node (here the floor) misses any translucent layer over
// an opaque receiver, grey or tinted alike (docs/rendering.md, `beer`), so for it only the
// colour is checked. Grey scenes cost nothing extra: no colour side channel, no glass layer.
// And the camera sees clear glass on a black background by its Fresnel rim.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/scene/surface_transmittance.h"
#include "experiments/source_paths.h"
#include "render/frame/reference_render.h"
#include "render/load/mesh_generators.h"
#include "render/load/scene_loader.h"
#include "strategies/shadow/probe.h"
#include "strategies/storage/dsm_storage.h"
#include "tests/support/shadow_methods.h"

namespace dv {
namespace {

Scene standin(const std::string& name) {
  return load_scene(test::source_dir() + "/experiments/scenes/" + name);
}

// Floor points (y = 0, on the floor's top face) whose light path crosses the caster's middle.
std::vector<dvec3> shadowed_floor_points() {
  std::vector<dvec3> points;
  for (int i = -2; i <= 2; ++i)
    for (int j = -2; j <= 2; ++j) points.push_back({0.12 * i, 0.0, 0.08 * j});
  return points;
}

ProbeResults probe(const SceneData& data, const std::string& method, const std::string& params,
                   const std::vector<dvec3>& points) {
  auto m = test::make_shadow_method(method, params);
  return probe_transmittance(Backend::cpu, data, *m, points);
}

struct Method {
  std::string name, params;
};

std::vector<Method> every_method_at_defaults() {
  std::vector<Method> methods = {{"shadowmap", ""}, {"transmittance-slicemap", ""}, {"auto", ""}};
  for (const std::string& storage : storage_registry().names())
    methods.push_back({"dsm", "storage=" + storage});
  return methods;
}

TEST(GlassShadows, RedSlabCastsAPartialRedShadowInTheReference) {
  const Scene scene = standin("glass-red-slab.json");
  const SceneData data(scene, Memory::host);
  const ProbeResults exact = probe(data, "reference", "", shadowed_floor_points());
  for (size_t i = 0; i < exact.rgb.size(); ++i) {
    const dvec3 t = exact.rgb[i];
    EXPECT_GT(exact.transmittance[i], 0.1) << i;
    EXPECT_LT(exact.transmittance[i], 0.5) << i;
    EXPECT_GT(t.x, 0.8) << i;   // red passes (two crossings of 1 - F ~ 0.96)
    EXPECT_LT(t.y, 0.05) << i;  // green and blue are filtered by (0.96 * 0.15)^2
    EXPECT_NEAR(t.y, t.z, 1e-12) << i;
  }
}

TEST(GlassShadows, EveryMethodFollowsTheGlassRuleOnTheRedSlab) {
  const Scene scene = standin("glass-red-slab.json");
  const SceneData data(scene, Memory::host);
  const std::vector<dvec3> points = shadowed_floor_points();
  const ProbeResults exact = probe(data, "reference", "", points);
  for (const Method& m : every_method_at_defaults()) {
    const ProbeResults r = probe(data, m.name, m.params, points);
    const bool in_numbers = m.params != "storage=beer";
    for (size_t i = 0; i < points.size(); ++i) {
      EXPECT_GT(r.rgb[i].x, 4.0 * r.rgb[i].y) << m.name << " " << m.params << ": not red";
      EXPECT_NEAR(r.rgb[i].y, r.rgb[i].z, 1e-6) << m.name << " " << m.params;
      if (!in_numbers) continue;
      EXPECT_NEAR(r.transmittance[i], exact.transmittance[i], 0.05) << m.name << " " << m.params;
      if (m.name == "dsm")
        for (int c = 0; c < 3; ++c)
          EXPECT_NEAR(r.rgb[i][c], exact.rgb[i][c], 0.05) << m.params << " channel " << c;
    }
  }
}

TEST(GlassShadows, TintedMediumBehindClearGlassKeepsItsColourInTheDsm) {
  const Scene scene = standin("glass-tinted-medium.json");
  const SceneData data(scene, Memory::host);
  const std::vector<dvec3> points = shadowed_floor_points();
  const ProbeResults exact = probe(data, "reference", "", points);
  for (size_t i = 0; i < points.size(); ++i) {
    EXPECT_GT(exact.rgb[i].x, 2.0 * exact.rgb[i].y) << i;  // the medium absorbs red least
    EXPECT_GT(exact.rgb[i].y, exact.rgb[i].z) << i;
  }
  std::vector<Method> methods = {{"auto", ""}};
  for (const std::string& storage : storage_registry().names())
    methods.push_back({"dsm", "storage=" + storage});
  for (const Method& m : methods) {
    const ProbeResults r = probe(data, m.name, m.params, points);
    for (size_t i = 0; i < points.size(); ++i) {
      EXPECT_GT(r.rgb[i].x, r.rgb[i].y) << m.name << " " << m.params;
      EXPECT_GT(r.rgb[i].y, r.rgb[i].z) << m.name << " " << m.params;
      if (m.params == "storage=beer") continue;
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(r.rgb[i][c], exact.rgb[i][c], 0.05) << m.name << " " << m.params << " " << c;
    }
  }
}

TEST(GlassShadows, GreyScenesCarryNoColourBytes) {
  const Scene scene = load_scene(test::source_dir() + "/experiments/scenes/translucent-boxes.json");
  const SceneData data(scene, Memory::host);
  auto dsm = test::make_shadow_method("dsm", "res=128");
  dsm->prepare(data, Backend::cpu, nullptr);
  const nlohmann::json stats = dsm->stats();
  ASSERT_TRUE(stats.contains("storage")) << stats.dump();
  EXPECT_FALSE(stats["storage"].contains("colour_bytes")) << stats.dump();
  auto map = test::make_shadow_method("shadowmap", "res=128");
  map->prepare(data, Backend::cpu, nullptr);
  EXPECT_EQ(map->stats()["bytes"].get<int64_t>(),
            int64_t(128 * 128 * sizeof(float)) * map->stats()["faces"].get<int64_t>());
  // The red slab's maps carry colour: 20 bytes per texel beside the storage's own.
  const Scene red = standin("glass-red-slab.json");
  const SceneData red_data(red, Memory::host);
  auto red_dsm = test::make_shadow_method("dsm", "res=128");
  red_dsm->prepare(red_data, Backend::cpu, nullptr);
  EXPECT_EQ(red_dsm->stats()["storage"]["colour_bytes"].get<int64_t>(), 128 * 128 * 20);
}

// The other colour scheme the issue asks to weigh: three curves, one storage per channel. Its
// maps are those of the scene with every colour and extinction replaced by one channel's (a grey
// scene each, so no side channel), 3x the bytes and generation. Measured against the oracle per
// channel on the floor and inside the tinted medium (where the side channel mixes the pane's
// grey and the medium's tint); the side channel is kept when it is as accurate within 0.01 and
// smaller. The numbers are printed for docs/rendering.md.
Scene channel_scene(Scene scene, int c) {
  for (Object& o : scene.objects) {
    o.material.color = dvec3(o.material.color[c]);
    if (o.interior.kind != InteriorKind::constant) continue;
    o.interior.sigma *= o.interior.sigma_tint[c];
    o.interior.sigma_tint = dvec3(1.0);
  }
  return scene;
}

int64_t dsm_bytes(ShadowMethod& m) {
  return m.stats()["storage"]["bytes_allocated"].get<int64_t>();
}

TEST(GlassShadows, SideChannelAgainstThreeCurves) {
  std::vector<dvec3> points = shadowed_floor_points();
  for (int i = -2; i <= 2; ++i) points.push_back({0.1 * i, 0.55, 0.05});  // in the medium
  for (const char* name : {"glass-red-slab.json", "glass-tinted-medium.json"}) {
    const Scene scene = standin(name);
    const SceneData data(scene, Memory::host);
    const ProbeResults exact = probe(data, "reference", "", points);
    for (const std::string storage : {"compact", "beer", "moments"}) {
      const std::string params = "res=512 storage=" + storage;
      auto side = test::make_shadow_method("dsm", params);
      const ProbeResults s = probe_transmittance(Backend::cpu, data, *side, points);
      dvec3 side_error(0.0), curve_error(0.0);
      int64_t curve_bytes = 0;
      for (int c = 0; c < 3; ++c) {
        const Scene grey = channel_scene(scene, c);
        const SceneData grey_data(grey, Memory::host);
        auto curve = test::make_shadow_method("dsm", params);
        const ProbeResults r = probe_transmittance(Backend::cpu, grey_data, *curve, points);
        curve_bytes += dsm_bytes(*curve);
        for (size_t i = 0; i < points.size(); ++i) {
          curve_error[c] += std::abs(r.transmittance[i] - exact.rgb[i][c]) / double(points.size());
          side_error[c] += std::abs(s.rgb[i][c] - exact.rgb[i][c]) / double(points.size());
        }
      }
      const int64_t side_bytes = dsm_bytes(*side);
      std::printf(
          "%s %s: side channel mean |error| r %.4f g %.4f b %.4f, %lld bytes; "
          "three curves r %.4f g %.4f b %.4f, %lld bytes\n",
          name, storage.c_str(), side_error.x, side_error.y, side_error.z, (long long)side_bytes,
          curve_error.x, curve_error.y, curve_error.z, (long long)curve_bytes);
      for (int c = 0; c < 3; ++c) EXPECT_LE(side_error[c], curve_error[c] + 0.01) << name << c;
      EXPECT_LT(side_bytes, curve_bytes) << name << " " << storage;
    }
  }
}

TEST(GlassShadows, ClearGlassShowsAFresnelRimOnBlack) {
  Scene scene;
  scene.source = "clear-glass";
  scene.meshes.push_back(make_icosphere(1.0, 4));
  Object sphere;
  sphere.mesh = 0;
  sphere.material.color = dvec3(1.0);
  sphere.material.alpha = 0.0;
  sphere.material.transmission = 1.0;
  sphere.material.specular = 0.0;  // no highlight: only the Fresnel reflection shows
  scene.objects.push_back(sphere);
  Light light;
  light.type = LightType::directional;
  light.direction = {0.0, 0.0, -1.0};
  scene.lights.push_back(light);
  scene.camera.position = {0.0, 0.0, 5.0};
  scene.camera.target = dvec3(0.0);
  scene.camera.width = 64;
  scene.camera.height = 64;
  scene.camera.fov_deg = 30.0;
  validate_scene(scene);
  const SceneData data(scene, Memory::host);
  auto none = test::make_shadow_method("none", "");
  const Image image = render_reference(Backend::cpu, data, scene.camera, *none, dvec3(0.0)).image;
  const dvec3 centre = image.at(32, 32);
  double rim = 0.0;  // the brightest pixel along the middle row: near the silhouette
  for (int x = 0; x < 64; ++x) rim = std::max(rim, image.at(x, 32).x);
  EXPECT_GT(centre.x, 0.0);  // visible everywhere on black
  EXPECT_GT(rim, 3.0 * centre.x);
}

}  // namespace
}  // namespace dv
