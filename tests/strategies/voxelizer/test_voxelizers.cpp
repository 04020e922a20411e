// exact and sat on hand-checked and brute-force voxel sets: a single triangle, the x-z
// projection sign case, an axis-aligned cube on voxel boundaries, degenerate triangles
// (segments, points), random triangles, and two huge triangles covering a whole slice.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "core/error.h"
#include "render/load/mesh_generators.h"
#include "strategies/voxelizer/sat_voxelizer.h"
#include "strategies/voxelizer/voxel_metrics.h"
#include "strategies/voxelizer/work_items.h"
#include "tests/strategies/voxelizer/voxel_meshes.h"
#include "tests/strategies/voxelizer/voxel_test_support.h"

namespace dv {
namespace {

using test::soup_of;
using test::VoxelSet;

VoxelSet exact_set(const std::vector<dvec3>& corners, ivec3 res) {
  return test::voxels_of(voxelize_exact(soup_of(corners), test::unit_grid(res), false).exact);
}

VoxelSet sat_set(const std::vector<dvec3>& corners, ivec3 res) {
  return test::voxels_of(voxelize_sat(Backend::cpu, soup_of(corners), test::unit_grid(res)).grid);
}

// Points spread over the triangle; the half-open voxel holding each must be set.
void expect_samples_covered(const std::vector<dvec3>& c, const VoxelSet& set, ivec3 res) {
  const int n = 40;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; i + j <= n; ++j) {
      const double a = double(i) / n, b = double(j) / n;
      const dvec3 p = c[0] + a * (c[1] - c[0]) + b * (c[2] - c[0]);
      const ivec3 v = glm::clamp(ivec3(glm::floor(p)), ivec3(0), res - 1);
      if (glm::any(glm::lessThan(p, dvec3(0.0))) || glm::any(glm::greaterThan(p, dvec3(res))))
        continue;
      EXPECT_TRUE(set.count({v.x, v.y, v.z})) << p.x << " " << p.y << " " << p.z;
    }
}

TEST(Voxelizers, SingleTriangleMatchesTheHandCountedSet) {
  // Right triangle x >= 0.5, y >= 0.5, x + y <= 5 in the plane z = 2.5: the closed voxel boxes
  // meeting it are (i, j, 2) with 0 <= i, j <= 4 and i + j <= 5 (corner contact included).
  const std::vector<dvec3> tri = {{0.5, 0.5, 2.5}, {4.5, 0.5, 2.5}, {0.5, 4.5, 2.5}};
  VoxelSet expected;
  for (int i = 0; i <= 4; ++i)
    for (int j = 0; j <= 4; ++j)
      if (i + j <= 5) expected.insert({i, j, 2});
  EXPECT_EQ(expected.size(), 19u);
  EXPECT_EQ(exact_set(tri, {8, 8, 32}), expected);
  EXPECT_EQ(sat_set(tri, {8, 8, 32}), expected);
}

TEST(Voxelizers, TiltedTriangleMatchesBruteForce) {
  const std::vector<dvec3> tri = {{1.2, 0.7, 3.1}, {9.6, 2.3, 7.9}, {3.4, 10.8, 1.6}};
  const ivec3 res{12, 12, 32};
  const VoxelSet brute = test::brute_force_exact(tri, res);
  EXPECT_GT(brute.size(), 80u);
  EXPECT_EQ(exact_set(tri, res), brute);
  EXPECT_EQ(sat_set(tri, res), brute);
  expect_samples_covered(tri, brute, res);
}

TEST(Voxelizers, XzProjectionSignCase) {
  // Dominant normal along -y: the projection along y decides the columns, and its 2D
  // orientation is +n.y only with (z, x) coordinates. With the sign taken from (x, z) the
  // edge tests reject every voxel.
  const std::vector<dvec3> tri = {{1.3, 2.2, 1.4}, {14.6, 3.1, 2.7}, {2.1, 4.3, 14.8}};
  const ivec3 res{16, 16, 32};
  SatTriangle t;
  ASSERT_TRUE(sat_setup(tri[0], tri[1], tri[2], res, t));
  EXPECT_EQ(t.axis, 1);
  EXPECT_LT(t.n.y, 0.0);
  const VoxelSet brute = test::brute_force_exact(tri, res);
  const VoxelSet sat = sat_set(tri, res);
  EXPECT_EQ(sat, brute);
  EXPECT_GT(sat.size(), 100u);
  EXPECT_LT(sat.size(), 200u);
  // The same test with the x-z orientation flipped finds nothing.
  for (SatEdge& e : t.edges[1]) {
    e.nu = -e.nu;
    e.nv = -e.nv;
  }
  for (int i = 0; i < 3; ++i) {
    const dvec3& p = tri[size_t(i)];
    SatEdge& e = t.edges[1][i];
    e.d = -(e.nu * p.z + e.nv * p.x) + std::max(0.0, e.nu) + std::max(0.0, e.nv);
  }
  int flipped = 0;
  for (int z = 0; z < res.z; ++z)
    for (int y = 0; y < res.y; ++y)
      for (int x = 0; x < res.x; ++x) flipped += sat_voxel_passes(t, ivec3(x, y, z));
  EXPECT_EQ(flipped, 0);
  RecordProperty("xz_case_voxels", int(sat.size()));
}

TEST(Voxelizers, AxisAlignedCubeOnVoxelBoundaries) {
  // Faces exactly on voxel planes set the voxels on both sides: [7, 24]^3 minus [9, 22]^3.
  const TriangleMesh cube = make_box(dvec3(8.0), dvec3(24.0));
  const TriangleSoup soup = triangle_soup(cube);
  const GridSpec spec = test::unit_grid({32, 32, 32});
  VoxelSet expected;
  for (int z = 7; z <= 24; ++z)
    for (int y = 7; y <= 24; ++y)
      for (int x = 7; x <= 24; ++x)
        if (!(x >= 9 && x <= 22 && y >= 9 && y <= 22 && z >= 9 && z <= 22))
          expected.insert({x, y, z});
  EXPECT_EQ(expected.size(), size_t(18 * 18 * 18 - 14 * 14 * 14));
  const ExactVoxelization exact = voxelize_exact(soup, spec, true);
  EXPECT_EQ(test::voxels_of(exact.exact), expected);
  const VoxelizeResult sat = voxelize_sat(Backend::cpu, soup, spec);
  EXPECT_EQ(test::voxels_of(sat.grid), expected);
  const VoxelMetrics m = compare_with_exact(sat.grid, exact);
  EXPECT_EQ(m.missing, 0);
  EXPECT_EQ(m.extra, 0);
  EXPECT_EQ(m.borderline, m.reference_filled);  // every voxel only touches a face
}

TEST(Voxelizers, DegenerateTrianglesAreSegmentsAndPoints) {
  const ivec3 res{10, 10, 32};
  // Segment through voxel interiors along x, written as (a, b, b).
  const std::vector<dvec3> segment = {{1.5, 2.5, 3.5}, {6.5, 2.5, 3.5}, {6.5, 2.5, 3.5}};
  VoxelSet expected;
  for (int i = 1; i <= 6; ++i) expected.insert({i, 2, 3});
  EXPECT_EQ(exact_set(segment, res), expected);
  EXPECT_EQ(sat_set(segment, res), expected);
  // Collinear triangle with distinct corners on a voxel edge line (y = 2, z = 3): 4 voxels
  // around the line per step.
  const std::vector<dvec3> edge_line = {{1.5, 2.0, 3.0}, {4.0, 2.0, 3.0}, {6.5, 2.0, 3.0}};
  expected.clear();
  for (int i = 1; i <= 6; ++i)
    for (int j = 1; j <= 2; ++j)
      for (int k = 2; k <= 3; ++k) expected.insert({i, j, k});
  EXPECT_EQ(exact_set(edge_line, res), expected);
  EXPECT_EQ(sat_set(edge_line, res), expected);
  // Points: inside one voxel, and on a voxel corner (8 voxels).
  const std::vector<dvec3> point = {{2.5, 2.5, 2.5}, {2.5, 2.5, 2.5}, {2.5, 2.5, 2.5}};
  EXPECT_EQ(sat_set(point, res), (VoxelSet{{2, 2, 2}}));
  EXPECT_EQ(exact_set(point, res), (VoxelSet{{2, 2, 2}}));
  const std::vector<dvec3> corner = {{2.0, 3.0, 4.0}, {2.0, 3.0, 4.0}, {2.0, 3.0, 4.0}};
  EXPECT_EQ(sat_set(corner, res).size(), 8u);
  EXPECT_EQ(exact_set(corner, res).size(), 8u);
  // A diagonal segment through the grid, against every voxel tested.
  const std::vector<dvec3> diagonal = {{0.3, 0.9, 1.7}, {9.1, 7.3, 28.4}, {0.3, 0.9, 1.7}};
  const ivec3 big{10, 10, 32};
  const VoxelSet brute = test::brute_force_exact(diagonal, big);
  EXPECT_GT(brute.size(), 30u);
  EXPECT_EQ(exact_set(diagonal, big), brute);
  EXPECT_EQ(sat_set(diagonal, big), brute);
  const VoxelizeResult r = voxelize_sat(Backend::cpu, soup_of(diagonal), test::unit_grid(big));
  EXPECT_EQ(r.counters["degenerate_triangles"].get<int64_t>(), 1);
  EXPECT_EQ(r.counters["work_items"].get<int64_t>(), 28);  // one per z slice 1..28
}

TEST(Voxelizers, RandomTrianglesAgreeWithBruteForce) {
  std::mt19937 rng(2024);
  std::uniform_real_distribution<double> coord(-2.0, 18.0), small(-1.5, 1.5);
  const ivec3 res{16, 16, 32};
  std::vector<dvec3> all;
  for (int t = 0; t < 60; ++t) {
    std::vector<dvec3> tri(3);
    const dvec3 base(coord(rng), coord(rng), coord(rng) * 1.5);
    const bool tiny = t % 3 == 0;
    for (dvec3& p : tri)
      p = tiny ? base + dvec3(small(rng), small(rng), small(rng))
               : dvec3(coord(rng), coord(rng), coord(rng) * 1.5);
    if (t % 10 == 7) tri[2] = 0.5 * (tri[0] + tri[1]);  // a collinear one now and then
    const VoxelSet brute = test::brute_force_exact(tri, res);
    EXPECT_EQ(exact_set(tri, res), brute) << "triangle " << t;
    EXPECT_EQ(sat_set(tri, res), test::brute_force_sat(tri, res)) << "triangle " << t;
    EXPECT_EQ(test::count_differences(sat_set(tri, res), brute), 0) << "triangle " << t;
    all.insert(all.end(), tri.begin(), tri.end());
  }
  // All at once (shared words, many work items) gives the union.
  EXPECT_EQ(sat_set(all, res), test::brute_force_sat(all, res));
}

TEST(Voxelizers, TwoHugeTrianglesFillTheirSlice) {
  const ivec3 res{256, 256, 32};
  const GridSpec spec = test::unit_grid(res);
  const TriangleSoup flat = soup_of({{-10.0, -10.0, 10.5},
                                     {266.0, -10.0, 10.5},
                                     {266.0, 266.0, 10.5},
                                     {-10.0, -10.0, 10.5},
                                     {266.0, 266.0, 10.5},
                                     {-10.0, 266.0, 10.5}});
  const VoxelizeResult r = voxelize_sat(Backend::cpu, flat, spec);
  EXPECT_EQ(r.grid.popcount(), 256 * 256);
  for (int y = 0; y < 256; y += 17)
    for (int x = 0; x < 256; x += 13) EXPECT_TRUE(r.grid.get(x, y, 10));
  // One work item per column of each triangle's range: the work is spread, not serialised.
  EXPECT_EQ(r.counters["work_items"].get<int64_t>(), 2 * 256 * 256);

  // A tilted pair across the whole grid against the exact reference.
  const TriangleSoup tilted = soup_of({{-1.0, -1.0, 3.3},
                                       {257.0, -1.0, 27.9},
                                       {257.0, 257.0, 21.2},
                                       {-1.0, -1.0, 3.3},
                                       {257.0, 257.0, 21.2},
                                       {-1.0, 257.0, 9.1}});
  const ExactVoxelization exact = voxelize_exact(tilted, spec, true);
  const VoxelizeResult t = voxelize_sat(Backend::cpu, tilted, spec);
  const VoxelMetrics m = compare_with_exact(t.grid, exact);
  EXPECT_GT(m.filled, 256 * 256);
  EXPECT_EQ(m.missing_outside_band, 0);
  EXPECT_EQ(m.extra_outside_band, 0);
  // The shared diagonal runs through voxel corners: disagreements there are rounding ties.
  EXPECT_LE(m.missing + m.extra, m.borderline);
  std::printf("tilted huge pair: exact %lld, sat %lld, missing %lld, extra %lld, band %lld\n",
              (long long)m.reference_filled, (long long)m.filled, (long long)m.missing,
              (long long)m.extra, (long long)m.borderline);
}

TEST(Voxelizers, RegistryCreatesBothAndRejectsUnknownNames) {
  auto sat = voxelizer_registry().create("SAT");
  EXPECT_EQ(sat->name(), "sat");
  EXPECT_TRUE(sat->supports(Backend::cpu));
  auto exact = voxelizer_registry().create("exact");
  EXPECT_FALSE(exact->supports(Backend::cuda));
  EXPECT_THROW(exact->voxelize(Backend::cuda, TriangleSoup{}, test::unit_grid({4, 4, 32})),
               InputError);
  try {
    voxelizer_registry().create("slicemapx");
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("sat"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("exact"), std::string::npos);
  }
  EXPECT_THROW(voxelizer_registry().create("sat", StrategyParams::parse({"tile=8"})), InputError);
  EXPECT_THROW(voxelizer_registry().create("sat", StrategyParams::parse({"small=-1"})), InputError);
  EXPECT_EQ(voxelizer_registry().create("sat", StrategyParams::parse({"small=9"}))->params(),
            nlohmann::json({{"small", 9}}));
}

// Appends from many threads at once: the entries' first items follow their order, each entry
// owns exactly its primitive's items, and every primitive is listed once.
TEST(PackedWorkList, ConcurrentAppendsGiveOrderedOffsets) {
  const int64_t n = 20000;
  const auto items_of = [](int64_t i) { return (i * 7919) % 13; };
  unsigned long long counter = 0;
  std::vector<int64_t> primitive(n, -1), first(n, -1);
  const PackedWorkList list{&counter, primitive.data(), first.data(), packed_item_bits(n)};
  cpu_parallel_for(n, [&](int64_t i) { list.append(i, items_of(i)); });
  int64_t total = 0;
  for (int64_t i = 0; i < n; ++i) total += items_of(i);
  ASSERT_EQ(list.entries(), n);
  ASSERT_EQ(list.items(), total);
  std::vector<int> seen(n, 0);
  for (int64_t e = 0; e < n; ++e) {
    ASSERT_GE(primitive[e], 0);
    ++seen[primitive[e]];
    const int64_t end = e + 1 < n ? first[e + 1] : total;
    EXPECT_EQ(end - first[e], items_of(primitive[e])) << "entry " << e;
  }
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), n);
  for (int64_t k = 0; k < total; k += 97) {
    const int64_t e = owner_of_item(list.firsts(), n, k);
    EXPECT_TRUE(first[e] <= k && k < first[e] + items_of(primitive[e])) << "item " << k;
  }
}

TEST(PackedWorkList, BatchesKeepEntriesAndItemsApart) {
  EXPECT_EQ(packed_work_list_batch(235136, int64_t(1) << 20), 235136);  // bunny x3 at 1024^3
  EXPECT_EQ(packed_work_list_batch(0, 100), 1);
  const int64_t max_items = int64_t(1) << 29;  // a 16384 x 16384 x 32 grid's columns
  const int64_t batch = packed_work_list_batch(int64_t(1) << 30, max_items);
  ASSERT_GE(batch, 1);
  EXPECT_LT(batch, int64_t(1) << 30);
  const auto fits = [&](int64_t b) {
    return static_cast<unsigned __int128>(b) * max_items <
           (static_cast<unsigned __int128>(1) << packed_item_bits(b));
  };
  EXPECT_TRUE(fits(batch));
  EXPECT_FALSE(fits(2 * batch));  // halving stops at the first batch that fits
}

}  // namespace
}  // namespace dv
