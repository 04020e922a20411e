// The shadowmap method against the exact oracle on opaque-only scenes, for spot, omni (six
// faces) and directional lights: answers agree except near shadow edges (aliasing), and the
// maps are built once however often the method is prepared; translucent surfaces and media
// boundaries cast by the depth map's opacity threshold.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "strategies/shadow/probe.h"
#include "tests/support/scene_builder.h"
#include "tests/support/shadow_methods.h"

namespace dv {
namespace {

using test::SceneBuilder;

// An opaque box and sphere over a floor; the light is added by the caller.
SceneBuilder opaque_scene() {
  SceneBuilder b;
  b.add(make_box({-3, -0.1, -3}, {3, 0, 3}));
  b.add(make_box({-0.9, 0, -0.4}, {-0.3, 0.8, 0.2}));
  Object& ball = b.add(make_icosphere(0.35, 3));
  ball.transform[3] = dvec4(0.6, 0.6, 0.3, 1.0);
  return b;
}

struct Agreement {
  double fraction;  // answers within 0.5 of the oracle
  int shadowed;     // oracle answers below 0.5
};

Agreement compare_on_floor(SceneBuilder& b, const std::string& params) {
  const SceneData data = b.build();
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-2.5, 2.5);
  std::vector<dvec3> points;
  for (int i = 0; i < 4000; ++i) points.push_back({u(rng), 1e-9, u(rng)});
  auto reference = shadow_registry().create("reference");
  auto shadowmap = test::make_shadow_method("shadowmap", params);
  const ProbeResults exact = probe_transmittance(Backend::cpu, data, *reference, points);
  const ProbeResults approx = probe_transmittance(Backend::cpu, data, *shadowmap, points);
  int agree = 0, shadowed = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    agree += std::abs(exact.transmittance[i] - approx.transmittance[i]) < 0.5;
    shadowed += exact.transmittance[i] < 0.5;
  }
  ::testing::Test::RecordProperty("agreement", std::to_string(double(agree) / points.size()));
  return {double(agree) / points.size(), shadowed};
}

TEST(ShadowMap, SpotMatchesOracleUpToEdges) {
  SceneBuilder b = opaque_scene();
  b.spot({0.5, 4.0, 0.8}, {-0.1, -1.0, -0.15}, 45.0);
  const Agreement a = compare_on_floor(b, "res=1024 pcf=1");
  EXPECT_GT(a.fraction, 0.985);
  EXPECT_GT(a.shadowed, 100);
}

TEST(ShadowMap, OmniUsesSixFaces) {
  SceneBuilder b = opaque_scene();
  b.omni({0.2, 1.6, -0.1});
  const Agreement a = compare_on_floor(b, "res=512 pcf=2");
  EXPECT_GT(a.fraction, 0.98);
  EXPECT_GT(a.shadowed, 100);
}

TEST(ShadowMap, DirectionalIsOrthographic) {
  SceneBuilder b = opaque_scene();
  b.directional({0.4, -1.0, 0.3});
  const Agreement a = compare_on_floor(b, "res=1024 pcf=1");
  EXPECT_GT(a.fraction, 0.985);
  EXPECT_GT(a.shadowed, 100);
}

// A depth map holds one caster per texel, so a fragment casts when its opacity reaches
// kDepthMapOpaqueAlpha: a faint quad (alpha 0.3) casts nothing, a denser one (0.7) a
// full shadow, and a glass box (alpha 0) holding a medium of opacity 1 - exp(-2) across it casts
// from its boundary.
TEST(ShadowMap, CastsByOpacityThresholdAndFromMediaBoundaries) {
  SceneBuilder b;
  b.add(make_box({-3, -0.1, -3}, {3, 0, 3}));
  b.add(make_quad(1.0), 0.3).transform[3] = dvec4(-1.5, 1.0, 0.0, 1.0);
  b.add(make_quad(1.0), 0.7).transform[3] = dvec4(0.0, 1.0, 0.0, 1.0);
  b.add(make_box({1.0, 0.8, -0.5}, {2.0, 1.2, 0.5}), 0.0, InteriorKind::constant, 5.0);
  b.directional({0.0, -1.0, 0.0});
  const SceneData data = b.build();
  const std::vector<dvec3> points = {{-1.5, 0.0, 0.0}, {0.0, 0.0, 0.0}, {1.5, 0.0, 0.0}};
  auto reference = shadow_registry().create("reference");
  auto shadowmap = test::make_shadow_method("shadowmap", "res=256 pcf=1");
  const ProbeResults exact = probe_transmittance(Backend::cpu, data, *reference, points);
  const ProbeResults map = probe_transmittance(Backend::cpu, data, *shadowmap, points);
  const double oracle[] = {0.7, 0.3, std::exp(-5.0 * 0.4)};
  const double cast[] = {1.0, 0.0, 0.0};
  for (size_t i = 0; i < points.size(); ++i) {
    EXPECT_NEAR(exact.transmittance[i], oracle[i], 1e-12) << i;
    EXPECT_EQ(map.transmittance[i], cast[i]) << i;
  }
}

TEST(ShadowMap, MapsAreBuiltOncePerScene) {
  SceneBuilder b = opaque_scene();
  b.spot({0.5, 4.0, 0.8}, {0.0, -1.0, 0.0}, 40.0);
  const SceneData data = b.build();
  auto method = shadow_registry().create("shadowmap", StrategyParams::parse({"res=64"}));
  method->prepare(data, Backend::cpu, &b.scene.camera);
  method->prepare(data, Backend::cpu, &b.scene.camera);
  EXPECT_EQ(method->stats()["maps_built"], 1);
  EXPECT_EQ(method->stats()["prepare_calls"], 2);
  EXPECT_EQ(method->stats()["bytes"], 64 * 64 * 4);
  EXPECT_THROW(shadow_registry().create("shadowmap", StrategyParams::parse({"res=0"})), InputError);
  EXPECT_THROW(shadow_registry().create("shadowmap", StrategyParams::parse({"pcf=2", "eps=1"})),
               InputError);
}

TEST(ShadowMap, FocusingOnTheCameraSharpensWhatItSees) {
  // A wide spot cone over a large floor, a camera looking at a small part of it: a focused
  // 128^2 map spends its texels there and matches the oracle better than an unfocused one;
  // moving the camera rebuilds a focused map.
  SceneBuilder b = opaque_scene();
  b.spot({0.0, 6.0, 0.0}, {0.0, -1.0, 0.0}, 70.0);
  b.scene.camera.position = {0.2, 2.5, 2.5};
  b.scene.camera.target = {0.0, 0.3, 0.0};
  b.scene.camera.fov_deg = 40.0;
  const SceneData data = b.build();
  auto reference = shadow_registry().create("reference");
  auto plain = shadow_registry().create("shadowmap", StrategyParams::parse({"res=128", "pcf=1"}));
  auto focused =
      shadow_registry().create("shadowmap", StrategyParams::parse({"res=128", "pcf=1", "focus=1"}));
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1.2, 1.2);
  std::vector<dvec3> points;
  for (int i = 0; i < 3000; ++i) points.push_back({u(rng), 1e-9, u(rng)});
  auto errors = [&](ShadowMethod& m) {
    const ShadowSourceVariant src = m.prepare(data, Backend::cpu, &b.scene.camera);
    int wrong = 0;
    for (const dvec3& p : points) {
      const double exact = test::oracle_at(data, 0, p);
      const double approx = std::visit(
          [&](const auto& source) {
            typename std::decay_t<decltype(source)>::Cursor c{};
            return source.transmittance(c, probe_receiver(data.view(), data.view().lights[0], p),
                                        0);
          },
          src);
      wrong += std::abs(exact - approx) >= 0.5;
    }
    return wrong;
  };
  const int plain_wrong = errors(*plain), focused_wrong = errors(*focused);
  ::testing::Test::RecordProperty("plain_wrong", plain_wrong);
  ::testing::Test::RecordProperty("focused_wrong", focused_wrong);
  EXPECT_LT(focused_wrong, plain_wrong);
  EXPECT_EQ(focused->stats()["maps_built"], 1);
  Camera moved = b.scene.camera;
  moved.position.x += 0.5;
  focused->prepare(data, Backend::cpu, &moved);
  EXPECT_EQ(focused->stats()["maps_built"], 2);
  plain->prepare(data, Backend::cpu, &moved);
  EXPECT_EQ(plain->stats()["maps_built"], 1);
}

}  // namespace
}  // namespace dv
