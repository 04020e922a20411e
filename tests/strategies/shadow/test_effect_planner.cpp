// The effect planner and the `auto` shadow method (strategies/shadow/effect_planner.h,
// auto_shadows.cpp) on small scenes: what each light gets (no map for a light that reaches no
// caster, a depth map when every caster is opaque, a deep map otherwise, volume sampling only
// with a volume in reach, omni faces only where casters are), maps built once over a static
// orbit and rebuilt only for the lights that reach an edited object, and planned answers equal
// to the "everything on" method (`dsm` for every light) where the planner skipped work; MASK
// textures planned as opaque, BLEND textures as translucent.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "engine/raster/camera_rays.h"
#include "experiments/source_paths.h"
#include "render/frame/raster_render.h"
#include "render/load/gltf_import.h"
#include "strategies/shadow/effect_planner.h"
#include "strategies/shadow/probe.h"
#include "tests/support/scene_builder.h"
#include "tests/support/shadow_methods.h"

namespace dv {
namespace {

using test::SceneBuilder;

constexpr char kParams[] = "res=128 eps=0.01";

// Lights of the mixed scene, in order.
enum MixedLight { kOpaqueSpot, kTranslucentSpot, kVolumeSpot, kUpwardSpot, kOmniInRange };

// A floor with three regions: an opaque box at x = -3, a translucent box at x = +3 and a
// volume at z = +3, each under its own narrow spot light; a spot light pointing up at nothing
// and an omni light of range 2 over the opaque box.
SceneBuilder mixed_scene() {
  SceneBuilder b;
  b.add(make_box({-6, -0.1, -6}, {6, 0, 6}));
  b.add(make_box({-3.4, 0, -0.4}, {-2.6, 0.8, 0.4}));
  b.add(make_box({2.6, 0, -0.4}, {3.4, 0.8, 0.4}), 0.5);
  VolumeGrid g;
  g.name = "puff";
  g.dims = {6, 6, 6};
  g.spacing = {0.2, 0.2, 0.2};
  g.origin = {-0.5, 0.1, 2.5};
  for (int64_t i = 0; i < g.voxel_count(); ++i) g.density.push_back(float(0.3 + 0.1 * (i % 5)));
  b.scene.volumes.push_back(g);
  Object& v = b.add(make_box(g.bounds().lo, g.bounds().hi), 0.0, InteriorKind::volume);
  v.interior.volume = 0;
  v.interior.transfer.points = {{0.0, dvec3(1.0), 0.0}, {1.0, dvec3(1.0), 3.0}};
  b.spot({-3, 4, 0}, {0, -1, 0}, 25.0);
  b.spot({3, 4, 0}, {0, -1, 0}, 25.0);
  b.spot({0, 4, 3}, {0, -1, 0}, 20.0);
  b.spot({0, 5, 0}, {0, 1, 0}, 30.0);
  b.omni({-3, 1.6, 0}).range = 2.0;
  b.scene.camera.position = {0, 7, 9};
  b.scene.camera.width = 96;
  b.scene.camera.height = 72;
  return b;
}

const nlohmann::json& light_plan(const ShadowMethod& m, int light) {
  static nlohmann::json plan;
  plan = m.plan();
  return plan.at("lights").at(size_t(light));
}

TEST(EffectPlanner, ConeTestIsConservativeAndOmniFacesFollowCasters) {
  SceneBuilder b;
  b.spot({0, 4, 0}, {0, -1, 0}, 20.0);
  b.omni({0, 0, 0});
  const SceneData data = b.build();
  const LightView& spot = data.host_lights()[0];
  // tan(20 deg) * 4 = 1.456: a box whose edge is just inside the cone at the floor is reached,
  // one a unit further out and one behind the light are not.
  EXPECT_TRUE(light_reaches(spot, Aabb{{1.4, -0.1, -0.1}, {2.4, 0.0, 0.1}}));
  EXPECT_FALSE(light_reaches(spot, Aabb{{2.5, -0.1, -0.1}, {3.5, 0.0, 0.1}}));
  EXPECT_FALSE(light_reaches(spot, Aabb{{-0.5, 5.0, -0.5}, {0.5, 6.0, 0.5}}));
  const LightView& omni = data.host_lights()[1];
  const Aabb above{{-0.2, 1.0, -0.2}, {0.2, 1.5, 0.2}};
  EXPECT_TRUE(omni_face_reaches(omni, 2, above));   // +Y
  EXPECT_FALSE(omni_face_reaches(omni, 3, above));  // -Y
  EXPECT_FALSE(omni_face_reaches(omni, 0, above));  // +X: the box stays within 45 degrees of +Y
  // A wide floor below is seen by the four side faces and -Y, not by +Y.
  const Aabb floor{{-6, -1.1, -6}, {6, -1.0, 6}};
  for (int f = 0; f < 6; ++f) EXPECT_EQ(omni_face_reaches(omni, f, floor), f != 2) << f;
}

TEST(EffectPlanner, EachLightGetsWhatItsCastersNeed) {
  SceneBuilder b = mixed_scene();
  const SceneData data = b.build();
  auto method = test::make_shadow_method("auto", kParams);
  method->prepare(data, Backend::cpu, &b.scene.camera);
  EXPECT_EQ(light_plan(*method, kOpaqueSpot)["method"], "shadowmap");
  EXPECT_EQ(light_plan(*method, kOpaqueSpot)["casters"], nlohmann::json({0, 1}));
  EXPECT_EQ(light_plan(*method, kTranslucentSpot)["method"], "dsm");
  EXPECT_EQ(light_plan(*method, kTranslucentSpot)["volume_sampling"], false);
  EXPECT_EQ(light_plan(*method, kVolumeSpot)["method"], "dsm");
  EXPECT_EQ(light_plan(*method, kVolumeSpot)["volume_sampling"], true);
  EXPECT_EQ(light_plan(*method, kUpwardSpot)["method"], "none");
  EXPECT_EQ(light_plan(*method, kUpwardSpot)["map"], "none");
  const nlohmann::json& omni = light_plan(*method, kOmniInRange);
  EXPECT_EQ(omni["method"], "shadowmap");
  EXPECT_EQ(omni["faces"], nlohmann::json({1, 1, 0, 1, 1, 1}));  // nothing above it
  EXPECT_EQ(method->stats()["maps_built"], 4);
  EXPECT_EQ(method->deep_shadow_maps(), nullptr);
}

TEST(EffectPlanner, OpaqueOnlySceneHasNoDeepMapAndNoVolumeSamples) {
  SceneBuilder b;
  b.add(make_box({-3, -0.1, -3}, {3, 0, 3}));
  b.add(make_box({-0.9, 0, -0.4}, {-0.3, 0.8, 0.2}));
  b.spot({0.5, 4.0, 0.8}, {-0.1, -1.0, -0.15}, 45.0);
  b.omni({0.2, 1.6, -0.1});
  b.directional({0.4, -1.0, 0.3});
  b.scene.camera.width = 64;
  b.scene.camera.height = 48;
  const SceneData data = b.build();
  auto method = test::make_shadow_method("auto", kParams);
  const RasterRenderResult r =
      render_raster(Backend::cpu, data, b.scene.camera, *method, dvec3(0.0));
  for (int l = 0; l < 3; ++l) {
    EXPECT_EQ(light_plan(*method, l)["method"], "shadowmap") << l;
    EXPECT_EQ(light_plan(*method, l)["volume_sampling"], false) << l;
  }
  EXPECT_EQ(r.render.counters.volume_samples, 0u);
  EXPECT_EQ(method->deep_shadow_maps(), nullptr);
}

TEST(EffectPlanner, LightThatReachesNoCasterGetsNoMap) {
  SceneBuilder b;
  b.add(make_box({-3, -0.1, -3}, {3, 0, 3}), 0.5);
  b.spot({0, 2, 0}, {0, 1, 0}, 30.0);  // points away from the floor
  b.omni({20, 1, 0}).range = 5.0;      // out of range
  const SceneData data = b.build();
  auto method = test::make_shadow_method("auto", kParams);
  method->prepare(data, Backend::cpu, &b.scene.camera);
  for (int l = 0; l < 2; ++l) {
    EXPECT_EQ(light_plan(*method, l)["method"], "none") << l;
    EXPECT_EQ(light_plan(*method, l)["map"], "none") << l;
  }
  EXPECT_EQ(method->stats()["maps_built"], 0);
}

TEST(EffectPlanner, StaticSceneBuildsEachMapOnceOverTenOrbitingFrames) {
  SceneBuilder b = mixed_scene();
  const SceneData data = b.build();
  auto method = test::make_shadow_method("auto", kParams);
  for (int f = 0; f < 10; ++f) {
    const Camera cam = orbit_camera(b.scene.camera, 90.0, f, 10);
    render_raster(Backend::cpu, data, cam, *method, dvec3(0.0));
    for (int l : {kOpaqueSpot, kTranslucentSpot, kVolumeSpot, kOmniInRange})
      EXPECT_EQ(light_plan(*method, l)["map"], f == 0 ? "built" : "reused") << f << " " << l;
  }
  EXPECT_EQ(method->stats()["maps_built"], 4);
  EXPECT_EQ(method->stats()["maps_reused"], 36);
}

TEST(EffectPlanner, MovingOneObjectRebuildsOnlyTheMapsThatReachIt) {
  SceneBuilder b = mixed_scene();
  const SceneData before = b.build();
  auto method = test::make_shadow_method("auto", kParams);
  method->prepare(before, Backend::cpu, nullptr);
  b.scene.objects[2].transform[3] = dvec4(0.2, 0.0, 0.1, 1.0);  // the translucent box
  const SceneData after = b.build();
  const ShadowSourceVariant planned = method->prepare(after, Backend::cpu, nullptr);
  EXPECT_EQ(light_plan(*method, kTranslucentSpot)["map"], "built");
  EXPECT_EQ(light_plan(*method, kTranslucentSpot)["map_reason"],
            "a caster it reaches changed, came or went");
  for (int l : {kOpaqueSpot, kVolumeSpot, kOmniInRange})
    EXPECT_EQ(light_plan(*method, l)["map"], "reused") << l;
  EXPECT_EQ(method->stats()["maps_built"], 5);
  // The reused maps answer as freshly built ones do wherever their light arrives (beyond the
  // omni light's range its map may still show the box where it was: no light arrives there).
  auto fresh = test::make_shadow_method("auto", kParams);
  std::vector<dvec3> points;
  for (int i = 0; i < 400; ++i) points.push_back({-6.0 + 0.03 * i, 1e-9, 0.05 * (i % 7) - 0.15});
  const ProbeResults a = probe_transmittance(Backend::cpu, after, *method, points);
  const ProbeResults c = probe_transmittance(Backend::cpu, after, *fresh, points);
  const LightView& omni = after.host_lights()[kOmniInRange];
  int compared = 0;
  for (size_t i = 0; i < points.size(); ++i)
    for (int l = 0; l < a.light_count; ++l) {
      if (l == kOmniInRange && glm::length(points[i] - omni.position) > omni.range) continue;
      EXPECT_EQ(a.transmittance[i * a.light_count + l], c.transmittance[i * c.light_count + l])
          << "point " << i << " light " << l;
      ++compared;
    }
  EXPECT_GT(compared, 1600);
}

// Planned answers against `dsm` for every light at the same resolution and eps: lights the
// planner gave a deep map answer exactly alike (the same faces and nodes), lights without casters
// are exactly lit, and the opaque-only ones (depth maps, nearest texel, the same receiver bias)
// may differ only where a float32 node depth and a float32 map depth straddle a receiver: at most
// 0.5% of the points (measured: none).
TEST(EffectPlanner, PlannedAnswersEqualEverythingOnWhereWorkWasSkipped) {
  SceneBuilder b = mixed_scene();
  const SceneData data = b.build();
  auto planned = test::make_shadow_method("auto", kParams);
  auto everything = test::make_shadow_method("dsm", kParams);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-5.0, 5.0), h(0.0, 1.5);
  std::vector<dvec3> points;
  for (int i = 0; i < 8000; ++i) points.push_back({u(rng), i % 2 ? 1e-9 : h(rng), u(rng)});
  const ProbeResults p = probe_transmittance(Backend::cpu, data, *planned, points);
  const ProbeResults e = probe_transmittance(Backend::cpu, data, *everything, points);
  const int lights = p.light_count;
  ASSERT_EQ(lights, 5);
  const LightView& omni = data.host_lights()[kOmniInRange];
  for (int l = 0; l < lights; ++l) {
    int compared = 0, differing = 0;
    double max_diff = 0.0;
    for (size_t i = 0; i < points.size(); ++i) {
      // Beyond its range a light gives nothing: the planner need not answer there.
      if (l == kOmniInRange && glm::length(points[i] - omni.position) > omni.range) continue;
      const double d = std::abs(p.transmittance[i * lights + l] - e.transmittance[i * lights + l]);
      ++compared;
      differing += d > 0.0;
      max_diff = std::max(max_diff, d);
    }
    RecordProperty("differing_light" + std::to_string(l), differing);
    if (l == kTranslucentSpot || l == kVolumeSpot || l == kUpwardSpot)
      EXPECT_EQ(differing, 0) << "light " << l << " max " << max_diff;
    else
      EXPECT_LE(differing, compared / 200) << "light " << l << " max " << max_diff;
    EXPECT_GT(compared, 400) << l;
  }
  // Rendered images: the same within 1e-6 per channel (measured: identical).
  const RasterRenderResult rp = render_raster(Backend::cpu, data, b.scene.camera, *planned, {});
  const RasterRenderResult re = render_raster(Backend::cpu, data, b.scene.camera, *everything, {});
  const std::vector<float>& x = rp.render.image.rgb;
  const std::vector<float>& y = re.render.image.rgb;
  ASSERT_EQ(x.size(), y.size());
  double max_pixel_diff = 0.0;
  for (size_t i = 0; i < x.size(); ++i)
    max_pixel_diff = std::max(max_pixel_diff, double(std::abs(x[i] - y[i])));
  RecordProperty("max_pixel_diff", std::to_string(max_pixel_diff));
  EXPECT_LE(max_pixel_diff, 1e-6);
}

// Texture alpha: a MASK-textured opaque quad is opaque where covered, so a depth map
// (which cuts it per texel) serves its light; a BLEND-textured one is translucent: a deep map.
TEST(EffectPlanner, MaskTexturesAreOpaqueAndBlendTexturesTranslucent) {
  const Scene standin =
      load_gltf_scene(test::source_dir() + "/tests/data/textured/alpha_mask_quad.gltf");
  for (const char* keep : {"mask", "blend"}) {
    Scene scene = standin;
    std::erase_if(scene.objects,
                  [&](const Object& o) { return o.name != keep && o.name != "floor"; });
    ASSERT_EQ(scene.objects.size(), 2u);
    const SceneData data(scene, Memory::host);
    const LightPlan plan = plan_light(data, 0);
    EXPECT_EQ(plan.method,
              std::string(keep) == "mask" ? PlannedMethod::shadowmap : PlannedMethod::dsm)
        << keep;
  }
}

TEST(EffectPlanner, ExplainStatesEachDecision) {
  SceneBuilder b = mixed_scene();
  const SceneData data = b.build();
  auto method = test::make_shadow_method("auto", kParams);
  method->prepare(data, Backend::cpu, nullptr);
  const std::string text = explain_plan(method->plan());
  EXPECT_NE(text.find("light 0 (spot): shadowmap, every caster it reaches is opaque"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("light 3 (spot): none, its cone and range reach no shadow caster; no map"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("1 of 6 cube faces"), std::string::npos) << text;
  EXPECT_EQ(text.find("camera rays: volume sampling only inside the 1 volume object\n"), 0u)
      << text;
}

}  // namespace
}  // namespace dv
