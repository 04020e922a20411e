// The transmittance-slicemap shadow method against the exact oracle: stacks of translucent
// quads of equal alpha under a spot and a directional light, where (1 - a)^n is exact away from
// slice boundaries, with every point-method voxelizer; opaque casters through the depth map;
// the mean opacity of mixed alphas in the stats; media casting from their boundaries;
// conservative voxelizers rejecting spot faces;
// CPU/CUDA parity (skipped without a GPU).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "cuda/device_memory.h"
#include "strategies/shadow/probe.h"
#include "tests/support/scene_builder.h"
#include "tests/support/shadow_methods.h"

namespace dv {
namespace {

using test::SceneBuilder;

constexpr double kAlpha = 0.3;
constexpr double kQuadY[] = {1.0, 1.6, 2.2, 2.8};

// Four horizontal quads 2 wide at kQuadY over an opaque floor whose top is at y = 0.
SceneBuilder quad_stack(double alpha_low = kAlpha, double alpha_high = kAlpha) {
  SceneBuilder b;
  b.add(make_box({-3, -0.1, -3}, {3, 0, 3}));
  for (int i = 0; i < 4; ++i) {
    Object& q = b.add(make_quad(2.0), i < 2 ? alpha_low : alpha_high);
    q.transform[3] = dvec4(0.0, kQuadY[i], 0.0, 1.0);
  }
  return b;
}

// Points above the floor inside the quads' footprint, between the layers (away from slice
// boundaries), and the number of quads above each.
struct Probe {
  std::vector<dvec3> points;
  std::vector<int> above;
};
Probe stack_points() {
  Probe p;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.8, 0.8);
  const double heights[] = {0.5, 1.3, 1.9, 2.5, 3.1};
  for (int h = 0; h < 5; ++h)
    for (int i = 0; i < 40; ++i) {
      p.points.push_back({u(rng), heights[h], u(rng)});
      p.above.push_back(4 - h);
    }
  return p;
}

std::unique_ptr<ShadowMethod> tsm(const std::string& params) {
  return test::make_shadow_method("transmittance-slicemap", params);
}

void expect_powers(SceneBuilder& b, const std::string& params) {
  const SceneData data = b.build();
  const Probe p = stack_points();
  auto method = tsm(params);
  const ProbeResults r = probe_transmittance(Backend::cpu, data, *method, p.points);
  for (size_t i = 0; i < p.points.size(); ++i) {
    const double expected = std::pow(1.0 - kAlpha, p.above[i]);
    EXPECT_NEAR(test::oracle_at(data, 0, p.points[i]), expected, 1e-12) << i;
    EXPECT_NEAR(r.transmittance[i], expected, 1e-12) << params << " point " << i;
  }
  EXPECT_EQ(method->stats()["casters"]["objects"], 4);
  EXPECT_FALSE(method->stats()["casters"]["alphas_differ"].get<bool>());
}

class StackByVoxelizer : public ::testing::TestWithParam<std::string> {
 protected:
  // The voxelizer and, for the atlas methods, a smaller atlas.
  std::string voxelizer() const {
    return " voxelizer=" + GetParam() + (GetParam() == "slicemap" ? "" : " voxelizer.atlas=256");
  }
};

TEST_P(StackByVoxelizer, SpotMatchesPowers) {
  SceneBuilder b = quad_stack();
  b.spot({0.0, 5.0, 0.0}, {0.0, -1.0, 0.0}, 40.0);
  expect_powers(b, "res=128 pcf=1" + voxelizer());
}

TEST_P(StackByVoxelizer, DirectionalMatchesPowers) {
  SceneBuilder b = quad_stack();
  b.directional({0.0, -1.0, 0.0});
  expect_powers(b, "res=128 pcf=1 slices=64" + voxelizer());
}

INSTANTIATE_TEST_SUITE_P(PointMethods, StackByVoxelizer,
                         ::testing::Values("slicemap", "atlas", "atlas-compute"));

TEST(TransmittanceSlicemap, ConservativeVoxelizersOnOrthographicGridsRejectSpots) {
  for (const char* v : {"sat", "exact"}) {
    SceneBuilder b = quad_stack();
    b.directional({0.0, -1.0, 0.0});
    expect_powers(b, std::string("res=64 pcf=1 voxelizer=") + v);
    SceneBuilder spot = quad_stack();
    spot.spot({0.0, 5.0, 0.0}, {0.0, -1.0, 0.0}, 40.0);
    const SceneData data = spot.build();
    auto method = tsm(std::string("res=64 voxelizer=") + v);
    try {
      method->prepare(data, Backend::cpu, nullptr);
      ADD_FAILURE() << v << " accepted a perspective grid";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("perspective"), std::string::npos) << e.what();
    }
  }
}

TEST(TransmittanceSlicemap, OpaqueCastersGoThroughTheDepthMap) {
  SceneBuilder b = quad_stack();
  b.add(make_box({1.5, 1.0, -0.5}, {2.5, 1.2, 0.5}));  // opaque, beside the stack
  b.directional({0.0, -1.0, 0.0});
  const SceneData data = b.build();
  const std::vector<dvec3> points = {{2.0, 0.5, 0.0}, {2.0, 1.5, 0.0}, {0.0, 0.5, 0.0}};
  auto method = tsm("res=128 pcf=1");
  const ProbeResults r = probe_transmittance(Backend::cpu, data, *method, points);
  const double expected[] = {0.0, 1.0, std::pow(1.0 - kAlpha, 4)};
  for (size_t i = 0; i < points.size(); ++i) {
    EXPECT_NEAR(test::oracle_at(data, 0, points[i]), expected[i], 1e-12);
    EXPECT_NEAR(r.transmittance[i], expected[i], 1e-12) << i;
  }
}

// Media boundaries cast: a glass box (alpha 0) holding a constant medium is a
// translucent caster whose two crossings give the medium's transmittance across it.
TEST(TransmittanceSlicemap, MediaCastFromTheirBoundaries) {
  SceneBuilder b;
  b.add(make_box({-3, -0.1, -3}, {3, 0, 3}));
  b.add(make_box({-0.5, 0.8, -0.5}, {0.5, 1.2, 0.5}), 0.0, InteriorKind::constant, 5.0);
  b.directional({0.0, -1.0, 0.0});
  const SceneData data = b.build();
  const dvec3 under(0.1, 0.0, -0.1);
  const double expected = std::exp(-5.0 * 0.4);
  EXPECT_NEAR(test::oracle_at(data, 0, under), expected, 1e-12);
  auto method = tsm("res=128 pcf=1");
  const ProbeResults r = probe_transmittance(Backend::cpu, data, *method, {under});
  EXPECT_NEAR(r.transmittance[0], expected, 1e-9);
  EXPECT_EQ(method->stats()["casters"]["objects"], 1);
}

TEST(TransmittanceSlicemap, MixedAlphasUseAndReportTheMean) {
  SceneBuilder b = quad_stack(0.2, 0.4);
  b.spot({0.0, 5.0, 0.0}, {0.0, -1.0, 0.0}, 40.0);
  const SceneData data = b.build();
  auto method = tsm("res=64 pcf=1");
  const ProbeResults r = probe_transmittance(Backend::cpu, data, *method, {{0.1, 0.5, 0.1}});
  EXPECT_NEAR(r.transmittance[0], std::pow(1.0 - 0.3, 4), 1e-12);
  EXPECT_NEAR(test::oracle_at(data, 0, {0.1, 0.5, 0.1}), 0.8 * 0.8 * 0.6 * 0.6, 1e-12);
  const nlohmann::json stats = method->stats();
  EXPECT_NEAR(stats["casters"]["alpha_mean"].get<double>(), 0.3, 1e-12);
  EXPECT_EQ(stats["casters"]["alpha_min"].get<double>(), 0.2);
  EXPECT_EQ(stats["casters"]["alpha_max"].get<double>(), 0.4);
  EXPECT_TRUE(stats["casters"]["alphas_differ"].get<bool>());
  EXPECT_NE(stats["not_represented"].get<std::string>().find("volumes"), std::string::npos);
}

TEST(TransmittanceSlicemap, BuildsOncePerSceneAndChecksParameters) {
  SceneBuilder b = quad_stack();
  b.omni({0.0, 5.0, 0.0});
  const SceneData data = b.build();
  auto method = tsm("res=32");
  method->prepare(data, Backend::cpu, nullptr);
  method->prepare(data, Backend::cpu, nullptr);
  EXPECT_EQ(method->stats()["maps_built"], 1);
  EXPECT_EQ(method->stats()["faces"], 6);
  EXPECT_THROW(tsm("slices=48"), InputError);
  EXPECT_THROW(tsm("slices=2048"), InputError);
  EXPECT_THROW(tsm("voxelizer=nope"), InputError);
  EXPECT_THROW(tsm("voxelizer.nope=1"), InputError);
  const auto names = shadow_registry().names();
  EXPECT_NE(std::find(names.begin(), names.end(), "transmittance-slicemap"), names.end());
}

TEST(TransmittanceSlicemap, CpuAndCudaAgree) {
  std::string why;
  if (!cuda_device_available(&why)) GTEST_SKIP() << "no CUDA device: " << why;
  SceneBuilder b = quad_stack(0.2, 0.4);
  b.add(make_box({1.5, 1.0, -0.5}, {2.5, 1.2, 0.5}));
  b.spot({0.3, 5.0, 0.2}, {-0.05, -1.0, 0.0}, 50.0);
  b.directional({0.2, -1.0, 0.1});
  validate_scene(b.scene);
  const SceneData host(b.scene, Memory::host), device(b.scene, Memory::device);
  const Probe p = stack_points();
  for (const char* v : {"slicemap", "atlas-compute"}) {
    const std::string params = std::string("res=96 pcf=2 slices=64 voxelizer=") + v;
    auto cpu = tsm(params), cuda = tsm(params);
    const ProbeResults a = probe_transmittance(Backend::cpu, host, *cpu, p.points);
    const ProbeResults g = probe_transmittance(Backend::cuda, device, *cuda, p.points);
    EXPECT_EQ(cpu->stats()["set_voxels"], cuda->stats()["set_voxels"]) << v;
    for (size_t i = 0; i < a.transmittance.size(); ++i)
      EXPECT_NEAR(a.transmittance[i], g.transmittance[i], 1e-12) << v << " " << i;
  }
}

}  // namespace
}  // namespace dv
