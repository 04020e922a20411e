// The fixed-size storages `beer` (UE 5's Beer shadow map) and `avsm` (Salvi et al. 2010) against
// closed forms, the exact-size function and the exact oracle: one constant-extinction slab is
// Beer's curve exactly; avsm with N at least the nodes a texel needs stores that function
// unchanged, and with fewer its error (measured against the oracle, reported) does not grow as
// N grows; each texel's recorded error bounds |V' - V|; an opaque surface leaves 0 behind it;
// many surfaces on one texel keep exactly N nodes inside the allocation; V' stays in [0, 1] and
// non-increasing in depth; CPU and CUDA store the same functions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <random>

#include "cuda/device_memory.h"
#include "strategies/shadow/shadow_method.h"
#include "tests/strategies/storage/storage_test_support.h"

namespace dv {
namespace {

// Maps whose lookups at texel-centre points need no receiver bias (as in test_dsm_lookups.cpp).
std::unique_ptr<DeepShadowMaps> unbiased_maps(const SceneData& data, const std::string& storage,
                                              const std::vector<std::string>& params, int res,
                                              float eps = 0.0f) {
  DsmSettings s = test::storage_settings(storage, params, eps, res);
  s.bias = 0.0;
  s.slope_bias = 0.0;
  auto maps = std::make_unique<DeepShadowMaps>(s);
  maps->generate(data, Backend::cpu);
  return maps;
}

double dsm_at(const DeepShadowMaps& maps, const dvec3& p) {
  DsmSource::Cursor cursor;
  return maps.source().transmittance(cursor, ShadowReceiver{p}, 0);
}

struct OraclePoint {
  dvec3 p;
  double exact;
};

// Points on texel-centre rays of light 0's only face (a spot light) at seeded random depths up to
// 1.2 scene diagonals, with the oracle's transmittance.
std::vector<OraclePoint> texel_centre_points(const SceneData& data, const DeepShadowMaps& maps,
                                             int count, unsigned seed) {
  const ShadowFace& face = maps.layout().faces[0];
  const int res = maps.resolution();
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> texel(0, res - 1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<OraclePoint> points;
  while (int(points.size()) < count) {
    const PixelRay ray = pixel_ray(face.projection, texel(rng), texel(rng));
    const dvec3 p = ray.origin + ray.direction * (u(rng) * 1.2 * data.view().diagonal);
    if (outside_light_cone(data.host_lights()[0], p)) continue;
    points.push_back({p, test::oracle_at(data, 0, p)});
  }
  return points;
}

struct ErrorFigures {
  double mean = 0.0, max = 0.0;
};

ErrorFigures oracle_error(const DeepShadowMaps& maps, const std::vector<OraclePoint>& points) {
  ErrorFigures e;
  for (const OraclePoint& q : points) {
    const double error = std::abs(dsm_at(maps, q.p) - q.exact);
    e.mean += error / double(points.size());
    e.max = std::max(e.max, error);
  }
  return e;
}

// Every texel's lookups of `approx` lie within its recorded error of the exact-size function.
void expect_within_recorded_error(const test::Generated& exact, const test::Generated& approx) {
  const std::vector<float> a = test::sample_lookups(exact, Backend::cpu);
  const std::vector<float> b = test::sample_lookups(approx, Backend::cpu);
  const std::vector<DsmTexelRecord>& records = approx.maps->records();
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i)
    ASSERT_LE(std::abs(a[i] - b[i]), records[i / test::kLookupDepths].error + 1e-5f) << i;
}

// V' in [0, 1] and non-increasing (up to one float rounding) over each texel's increasing lookup
// depths.
void expect_bounded_and_monotone(const test::Generated& g) {
  const std::vector<float> v = test::sample_lookups(g, Backend::cpu);
  for (size_t i = 0; i < v.size(); ++i) {
    ASSERT_GE(v[i], 0.0f) << i;
    ASSERT_LE(v[i], 1.0f) << i;
    if (i % test::kLookupDepths != 0) {
      ASSERT_LE(v[i], v[i - 1] + 1e-7f) << i;
    }
  }
}

Scene spot_scene(test::SceneBuilder& b) {
  b.spot(dvec3(0.2, 4.5, 0.1), dvec3(0.0, -1.0, 0.0), 30.0);
  validate_scene(b.scene);
  return b.scene;
}

// One slab of constant extinction 1.5 (invisible surfaces, alpha 0) under a spot light.
Scene constant_slab() {
  test::SceneBuilder b;
  b.add(make_box(dvec3(-3.0, 1.0, -3.0), dvec3(3.0, 1.8, 3.0)), 0.0, InteriorKind::constant, 1.5);
  return spot_scene(b);
}

// Three slabs: a medium with invisible surfaces, a medium behind translucent surfaces, and a
// translucent box without interior.
Scene three_slabs() {
  test::SceneBuilder b;
  b.add(make_box(dvec3(-3.0, 2.4, -3.0), dvec3(3.0, 3.0, 3.0)), 0.0, InteriorKind::constant, 0.8);
  b.add(make_box(dvec3(-3.0, 1.2, -3.0), dvec3(3.0, 1.8, 3.0)), 0.2, InteriorKind::constant, 2.0);
  b.add(make_box(dvec3(-3.0, 0.3, -3.0), dvec3(3.0, 0.6, 3.0)), 0.3);
  return spot_scene(b);
}

// `count` parallel quads of opacity `alpha`, 0.1 apart, the last at y = 0.
Scene stacked_quads(int count, double alpha) {
  test::SceneBuilder b;
  for (int i = 0; i < count; ++i) {
    TriangleMesh q = make_quad(8.0);
    for (dvec3& v : q.positions) v.y = 0.1 * i;
    b.add(std::move(q), alpha);
  }
  return spot_scene(b);
}

TEST(BeerStorage, ConstantSlabIsBeersCurveExactly) {
  const SceneData data(constant_slab(), Memory::host);
  const auto beer = unbiased_maps(data, "beer", {}, 32);
  const auto points = texel_centre_points(data, *beer, 2000, 1);
  int inside = 0;
  for (const OraclePoint& q : points) {
    ASSERT_NEAR(dsm_at(*beer, q.p), q.exact, 2e-6) << q.p.x << "," << q.p.y << "," << q.p.z;
    inside += q.p.y > 1.0 && q.p.y < 1.8;
  }
  EXPECT_GT(inside, 100);
  EXPECT_EQ(beer->figures()["bytes_allocated"], 16 * 32 * 32);
  EXPECT_EQ(beer->figures()["max_layers"], 2);
}

TEST(AvsmStorage, EnoughNodesStoreTheExactSizeFunction) {
  for (const Scene& scene : {stacked_quads(6, 0.3), test::scene_file("translucent-boxes.json")}) {
    const test::Generated exact = test::generate(scene, Backend::cpu, "compact", {}, 0.0f);
    const int needed = exact.maps->figures()["max_layers"].get<int>();
    ASSERT_LE(needed, kAvsmMaxNodes);
    ASSERT_GT(needed, 4);
    const test::Generated avsm = test::generate(
        scene, Backend::cpu, "avsm", {"nodes=" + std::to_string(std::max(needed, 2))}, 0.0f);
    const nlohmann::json& f = avsm.maps->figures();
    EXPECT_EQ(f["overflowed_texels"], 0) << f.dump();
    EXPECT_EQ(f["nodes"], exact.maps->figures()["nodes"]);
    EXPECT_EQ(f["max_error"], 0.0);
    test::expect_same_lookups(exact, avsm, Backend::cpu);
    // One node fewer than the deepest texel needs: that texel is approximated, within its bound.
    const test::Generated fewer =
        test::generate(scene, Backend::cpu, "avsm", {"nodes=" + std::to_string(needed - 1)}, 0.0f);
    EXPECT_GT(fewer.maps->figures()["overflowed_texels"].get<int64_t>(), 0);
    EXPECT_EQ(fewer.maps->figures()["max_layers"], needed - 1);
    expect_within_recorded_error(exact, fewer);
  }
}

TEST(AvsmStorage, ErrorAgainstTheOracleDoesNotGrowWithNodes) {
  const SceneData data(three_slabs(), Memory::host);
  const test::Generated exact = test::generate(three_slabs(), Backend::cpu, "compact", {}, 0.0f);
  const std::vector<OraclePoint> points =
      texel_centre_points(data, *unbiased_maps(data, "compact", {}, 32), 3000, 2);
  const ErrorFigures compact = oracle_error(*unbiased_maps(data, "compact", {}, 32, 0.01f), points);
  const ErrorFigures beer = oracle_error(*unbiased_maps(data, "beer", {}, 32), points);
  std::printf(
      "three slabs, 3000 points: compact eps 0.01 mean %.6f max %.6f; beer mean %.6f max "
      "%.6f; exact function needs %d nodes at most\n",
      compact.mean, compact.max, beer.mean, beer.max,
      exact.maps->figures()["max_layers"].get<int>());
  ErrorFigures previous{1.0, 1.0};
  for (int n : {2, 4, 8, 16, 32}) {
    const std::string nodes = "nodes=" + std::to_string(n);
    const ErrorFigures e = oracle_error(*unbiased_maps(data, "avsm", {nodes}, 32), points);
    std::printf("avsm N=%d: mean %.6f max %.6f\n", n, e.mean, e.max);
    RecordProperty("avsm_" + std::to_string(n) + "_mean_error", std::to_string(e.mean));
    EXPECT_LE(e.mean, previous.mean + 1e-9) << "N = " << n;
    EXPECT_LE(e.max, previous.max + 1e-9) << "N = " << n;
    previous = e;
    expect_within_recorded_error(
        exact, test::generate(three_slabs(), Backend::cpu, "avsm", {nodes}, 0.0f));
  }
  EXPECT_LT(previous.mean, 0.01);  // N = 32 is close to the exact function
  EXPECT_LT(previous.mean, beer.mean);
  expect_within_recorded_error(exact,
                               test::generate(three_slabs(), Backend::cpu, "beer", {}, 0.0f));
}

TEST(FixedNodeStorages, OpaqueSurfaceLeavesZeroBehindIt) {
  test::SceneBuilder b;
  for (const auto& [y, alpha] : {std::pair{1.0, 0.5}, std::pair{0.0, 1.0}}) {
    TriangleMesh q = make_quad(8.0);
    for (dvec3& v : q.positions) v.y = y;
    b.add(std::move(q), alpha);
  }
  const SceneData data(spot_scene(b), Memory::host);
  const auto beer = unbiased_maps(data, "beer", {}, 16);
  const auto avsm = unbiased_maps(data, "avsm", {"nodes=4"}, 16);
  const PixelRay ray = pixel_ray(beer->layout().faces[0].projection, 9, 6);
  const double t_upper = -3.5 / ray.direction.y, t_lower = -4.5 / ray.direction.y;
  const auto at = [&](const DeepShadowMaps& m, double t) {
    return dsm_at(m, ray.origin + ray.direction * t);
  };
  for (const DeepShadowMaps* m : {beer.get(), avsm.get()}) {
    EXPECT_EQ(at(*m, 0.5 * t_upper), 1.0);
    EXPECT_EQ(at(*m, t_upper), 1.0);  // on the surface: before its step
    EXPECT_EQ(at(*m, 1.001 * t_lower), 0.0);
    EXPECT_EQ(at(*m, 2.0 * t_lower), 0.0);
  }
  // Four nodes hold this function exactly; Beer's exponential from 0.5 towards the opaque exit
  // darkens the span between the surfaces (the floor 1e-6 at the exit: 0.5 (2e-6)^0.5 midway).
  const double mid = 0.5 * (t_upper + t_lower);
  EXPECT_NEAR(at(*avsm, mid), 0.5, 1e-6);
  EXPECT_NEAR(at(*beer, mid), 0.5 * std::sqrt(2e-6), 1e-6);
  EXPECT_EQ(test::oracle_at(data, 0, ray.origin + ray.direction * mid), 0.5);
}

TEST(FixedNodeStorages, ManySurfacesOnATexelStayInsideNNodes) {
  const Scene scene = stacked_quads(40, 0.05);
  const test::Generated exact = test::generate(scene, Backend::cpu, "compact", {}, 0.0f);
  EXPECT_EQ(exact.maps->figures()["max_layers"], 80);
  for (int n : {4, 16}) {
    const test::Generated avsm =
        test::generate(scene, Backend::cpu, "avsm", {"nodes=" + std::to_string(n)}, 0.0f);
    const nlohmann::json& f = avsm.maps->figures();
    const int64_t texels = f["texels"].get<int64_t>();
    EXPECT_EQ(f["max_layers"], n);
    EXPECT_EQ(f["bytes_allocated"], texels * n * 8);
    EXPECT_EQ(f["strategy"]["bytes_per_texel"], n * 8);
    EXPECT_GT(f["overflowed_texels"].get<int64_t>(), 0);
    for (const DsmTexelRecord& r : avsm.maps->records()) {
      ASSERT_LE(r.stored, n);
      ASSERT_LE(r.stored, r.nodes);
    }
    expect_bounded_and_monotone(avsm);
    expect_within_recorded_error(exact, avsm);
  }
  const test::Generated beer = test::generate(scene, Backend::cpu, "beer", {}, 0.0f);
  EXPECT_EQ(beer.maps->figures()["bytes_allocated"],
            beer.maps->figures()["texels"].get<int64_t>() * 16);
  expect_bounded_and_monotone(beer);
  expect_within_recorded_error(exact, beer);
}

TEST(FixedNodeStorages, VisibilityStaysInUnitRangeAndNonIncreasing) {
  for (const Scene& scene : {test::random_scene(5), test::scene_file("demo.json"),
                             test::scene_file("intersecting-volumes.json")})
    for (const auto& [name, params] : {std::pair<const char*, std::vector<std::string>>{"beer", {}},
                                       {"avsm", {"nodes=4"}},
                                       {"avsm", {"nodes=16"}}})
      expect_bounded_and_monotone(test::generate(scene, Backend::cpu, name, params, 0.02f));
}

TEST(FixedNodeStorages, BadParametersAreRejected) {
  EXPECT_THROW(storage_registry().create("avsm", StrategyParams::parse({"nodes=1"})), InputError);
  EXPECT_THROW(storage_registry().create("avsm", StrategyParams::parse({"nodes=33"})), InputError);
  EXPECT_THROW(storage_registry().create("beer", StrategyParams::parse({"nodes=4"})), InputError);
  EXPECT_NO_THROW(
      shadow_registry().create("dsm", StrategyParams::parse({"storage=avsm", "storage.nodes=16"})));
  EXPECT_EQ(storage_registry().create("avsm")->params()["nodes"], 8);
}

// CPU and CUDA: the same stored node counts and lookups, up to the ulp differences of the two
// math libraries' exp (walk samples) and log (Beer's lookup): texels whose nodes differ stay
// rare and within their recorded error.
TEST(FixedNodeStorages, CpuAndCudaAgree) {
  std::string why;
  if (!cuda_device_available(&why)) GTEST_SKIP() << "needs a GPU: " << why;
  for (const char* file : {"demo.json", "ct-phantom.json", "intersecting-volumes.json"})
    for (const auto& [name, params] :
         {std::pair<const char*, std::vector<std::string>>{"beer", {}}, {"avsm", {"nodes=8"}}}) {
      const Scene scene = test::scene_file(file);
      const test::Generated cpu = test::generate(scene, Backend::cpu, name, params, 0.02f, 48);
      const test::Generated gpu = test::generate(scene, Backend::cuda, name, params, 0.02f, 48);
      const std::vector<DsmTexelRecord>& a = cpu.maps->records();
      const std::vector<DsmTexelRecord>& b = gpu.maps->records();
      ASSERT_EQ(a.size(), b.size());
      int64_t differ = 0;
      for (size_t i = 0; i < a.size(); ++i) differ += a[i].stored != b[i].stored;
      EXPECT_LE(double(differ), 1e-4 * double(a.size())) << file << " " << name;
      const std::vector<float> va = test::sample_lookups(cpu, Backend::cpu);
      const std::vector<float> vb = test::sample_lookups(gpu, Backend::cuda);
      ASSERT_EQ(va.size(), vb.size());
      int64_t far_apart = 0;
      for (size_t i = 0; i < va.size(); ++i) {
        const DsmTexelRecord& r = a[i / test::kLookupDepths];
        const DsmTexelRecord& s = b[i / test::kLookupDepths];
        const float diff = std::abs(va[i] - vb[i]);
        far_apart += diff > 1e-5f;
        ASSERT_LE(diff, std::max(r.error, s.error) + 1e-5f) << file << " " << name << " " << i;
      }
      EXPECT_LE(double(far_apart), 1e-3 * double(va.size())) << file << " " << name;
      RecordProperty(std::string("lookups_apart_") + name + "_" + file, std::to_string(far_apart));
    }
}

}  // namespace
}  // namespace dv
