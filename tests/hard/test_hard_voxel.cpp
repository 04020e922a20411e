// Hard cases of the conservative voxelizers (exact on the CPU, sat on every backend) with
// closed-form voxel sets: faces exactly on voxel boundaries (a closed voxel box touching a face
// is set, so a face on the plane between slices 31 and 32 sets both, in two different words),
// vertices on grid corners, triangles far smaller than a voxel, triangles covering the whole
// grid (also 1e90 voxels wide), a non-cubic grid with non-cubic voxels, depths 1024 and 2048, and a
// grid of more than 2^31 voxels (16384 x 4100 x 32, 269 MB of words) where an int32 voxel index
// would overflow.
#include <gtest/gtest.h>

#include <set>

#include "strategies/voxelizer/sat_voxelizer.h"
#include "tests/hard/hard_test_support.h"
#include "tests/strategies/voxelizer/voxel_meshes.h"
#include "tests/strategies/voxelizer/voxel_test_support.h"

namespace dv::test {
namespace {

// Two triangles covering the plane z = z0 of a grid of `res` voxels and overshooting it by 5.
std::vector<dvec3> slice_plane(ivec3 res, double z0) {
  const double x0 = -5.0, y0 = -5.0, x1 = res.x + 5.0, y1 = res.y + 5.0;
  return {{x0, y0, z0}, {x1, y0, z0}, {x1, y1, z0}, {x0, y0, z0}, {x1, y1, z0}, {x0, y1, z0}};
}

VoxelSet whole_slices(ivec3 res, std::initializer_list<int> slices) {
  VoxelSet out;
  for (int z : slices)
    for (int y = 0; y < res.y; ++y)
      for (int x = 0; x < res.x; ++x) out.insert({x, y, z});
  return out;
}

class HardVoxelizers : public HardOnBackends {
 protected:
  // sat on this test's backend, and exact (CPU reference) on the CPU run only.
  void expect_voxels(const std::vector<dvec3>& corners, const GridSpec& spec,
                     const VoxelSet& expected, const char* what) {
    EXPECT_EQ(voxels_of(voxelize_sat(GetParam(), soup_of(corners), spec).grid), expected)
        << "sat: " << what;
    if (GetParam() == Backend::cpu) {
      EXPECT_EQ(voxels_of(voxelize_exact(soup_of(corners), spec, false).exact), expected)
          << "exact: " << what;
    }
  }
};

TEST_P(HardVoxelizers, FacesOnSliceAndWordBoundaries) {
  const ivec3 res{5, 3, 96};
  const GridSpec spec = unit_grid(res);
  expect_voxels(slice_plane(res, 32.0), spec, whole_slices(res, {31, 32}), "z = 32");
  expect_voxels(slice_plane(res, 31.0), spec, whole_slices(res, {30, 31}), "z = 31");
  expect_voxels(slice_plane(res, 63.5), spec, whole_slices(res, {63}), "z = 63.5");
  expect_voxels(slice_plane(res, 0.0), spec, whole_slices(res, {0}), "lower face");
  expect_voxels(slice_plane(res, 96.0), spec, whole_slices(res, {95}), "upper face");
  expect_voxels(slice_plane(res, 96.0 + 1e-9), spec, {}, "just above the grid");
}

TEST_P(HardVoxelizers, VerticesOnGridCorners) {
  // x, y >= 0, x + y <= 4 in the plane z = 32: closed boxes (i, j, 31) and (i, j, 32) with
  // i + j <= 4 meet it (the box's lowest corner is its nearest point): 15 columns, 2 slices.
  const ivec3 res{8, 8, 64};
  VoxelSet expected;
  for (int i = 0; i <= 4; ++i)
    for (int j = 0; i + j <= 4; ++j) expected.insert({i, j, 31}), expected.insert({i, j, 32});
  ASSERT_EQ(expected.size(), 30u);
  expect_voxels({{0, 0, 32}, {4, 0, 32}, {0, 4, 32}}, unit_grid(res), expected, "corner triangle");
}

TEST_P(HardVoxelizers, TrianglesMuchSmallerThanAVoxel) {
  const ivec3 res{8, 8, 64};
  const dvec3 c(2.5, 3.5, 40.5);
  const double d = 1e-3;
  expect_voxels({c, c + dvec3(d, 0, 0), c + dvec3(0, d, d)}, unit_grid(res), {{2, 3, 40}},
                "inside one voxel");
  // Around the grid corner (2, 3, 32) in the plane z = 32: the 8 voxels sharing that corner.
  const dvec3 k(2.0, 3.0, 32.0);
  VoxelSet corner;
  for (int x : {1, 2})
    for (int y : {2, 3})
      for (int z : {31, 32}) corner.insert({x, y, z});
  expect_voxels({k + dvec3(-d, -d, 0), k + dvec3(2 * d, -d, 0), k + dvec3(-d, 2 * d, 0)},
                unit_grid(res), corner, "around a grid corner");
}

TEST_P(HardVoxelizers, TriangleCoveringTheWholeGridDiagonally) {
  // The plane x = y through the whole grid: voxels with |i - j| <= 1 touch it (closed boxes).
  const ivec3 res{6, 6, 32};
  VoxelSet expected;
  for (int z = 0; z < res.z; ++z)
    for (int i = 0; i < res.x; ++i)
      for (int j = std::max(0, i - 1); j <= std::min(res.y - 1, i + 1); ++j)
        expected.insert({i, j, z});
  const std::vector<dvec3> plane = {{-10, -10, -10}, {20, 20, -10}, {20, 20, 80},
                                    {-10, -10, -10}, {20, 20, 80},  {-10, -10, 80}};
  expect_voxels(plane, unit_grid(res), expected, "x = y");
}

// Triangles reaching 1e90 voxels beyond a small grid: their squared edges and normal (about
// 1e361) overflow a double, so the degenerate rule compares scaled quantities; these are fat
// triangles, each a whole slice of the grid and none degenerate.
TEST_P(HardVoxelizers, TrianglesFarLargerThanTheGrid) {
  const ivec3 res{6, 5, 64};
  const double b = 1e90;
  const std::vector<dvec3> horizontal = {{-b, -b, 2.5}, {b, -b, 2.5}, {b, b, 2.5},
                                         {-b, -b, 2.5}, {b, b, 2.5},  {-b, b, 2.5}};
  expect_voxels(horizontal, unit_grid(res), whole_slices(res, {2}), "z = 2.5, 1e90 wide");
  VoxelSet column_slice;
  for (int z = 0; z < res.z; ++z)
    for (int y = 0; y < res.y; ++y) column_slice.insert({3, y, z});
  const std::vector<dvec3> vertical = {{3.5, -b, -b}, {3.5, b, -b}, {3.5, b, b},
                                       {3.5, -b, -b}, {3.5, b, b},  {3.5, -b, b}};
  expect_voxels(vertical, unit_grid(res), column_slice, "x = 3.5, 1e90 wide");
  const VoxelizeResult r = voxelize_sat(GetParam(), soup_of(vertical), unit_grid(res));
  EXPECT_EQ(r.counters["degenerate_triangles"].get<int64_t>(), 0);
}

TEST_P(HardVoxelizers, NonCubicGridAndVoxels) {
  // 7 x 3 x 96 voxels of 0.5 x 2 x 0.25 over [-1, 2.5] x [2, 8] x [5, 29]: the plane x = 0.5
  // is the boundary between voxel columns 2 and 3.
  const ivec3 res{7, 3, 96};
  const GridSpec spec = make_box_grid(res, Aabb{dvec3(-1.0, 2.0, 5.0), dvec3(2.5, 8.0, 29.0)});
  VoxelSet expected;
  for (int z = 0; z < res.z; ++z)
    for (int y = 0; y < res.y; ++y) expected.insert({2, y, z}), expected.insert({3, y, z});
  const std::vector<dvec3> plane = {{0.5, 0, 0}, {0.5, 10, 0},  {0.5, 10, 40},
                                    {0.5, 0, 0}, {0.5, 10, 40}, {0.5, 0, 40}};
  expect_voxels(plane, spec, expected, "x = 0.5");
}

class HardDeepGrids : public ::testing::TestWithParam<std::tuple<Backend, int>> {
 protected:
  void SetUp() override {
    std::string why;
    if (std::get<0>(GetParam()) == Backend::cuda && !cuda_device_available(&why))
      GTEST_SKIP() << "the CUDA run of this hard case needs a GPU: " << why;
  }
};

// Depths 1024 and 2048: a face on every word boundary z = 32 m sets slices 32 m - 1 and 32 m
// (bit 31 of word m - 1, bit 0 of word m), and a vertical plane fills whole columns.
TEST_P(HardDeepGrids, EveryWordBoundaryAndFullColumns) {
  const auto [backend, depth] = GetParam();
  const ivec3 res{4, 3, depth};
  const GridSpec spec = unit_grid(res);
  std::vector<dvec3> faces;
  for (int m = 1; m < depth / 32; m += 7) {
    const std::vector<dvec3> p = slice_plane(res, 32.0 * m);
    faces.insert(faces.end(), p.begin(), p.end());
  }
  const VoxelGrid grid = voxelize_sat(backend, soup_of(faces), spec).grid.copy_to(Memory::host);
  int64_t expected = 0;
  for (int m = 1; m < depth / 32; m += 7) {
    expected += 2 * res.x * res.y;
    for (int z : {32 * m - 1, 32 * m}) {
      EXPECT_TRUE(grid.get(0, 0, z)) << z;
      EXPECT_TRUE(grid.get(3, 2, z)) << z;
    }
    EXPECT_FALSE(grid.get(1, 1, 32 * m + 1));
  }
  EXPECT_EQ(grid.popcount(), expected);

  const std::vector<dvec3> wall = {{1.5, -1, -1}, {1.5, 9, -1},          {1.5, 9, depth + 1.0},
                                   {1.5, -1, -1}, {1.5, 9, depth + 1.0}, {1.5, -1, depth + 1.0}};
  const VoxelGrid column = voxelize_sat(backend, soup_of(wall), spec).grid.copy_to(Memory::host);
  EXPECT_EQ(column.popcount(), int64_t(res.y) * depth);
  for (int z : {0, 31, 32, depth / 2, depth - 1}) EXPECT_TRUE(column.get(1, 2, z)) << z;
}

INSTANTIATE_TEST_SUITE_P(Backends, HardDeepGrids,
                         ::testing::Combine(::testing::Values(Backend::cpu, Backend::cuda),
                                            ::testing::Values(1024, 2048)));

// 16384 x 4100 x 32 = 2,149,580,800 voxels (> 2^31 = 2,147,483,648): the counts are int64
// (GridSpec::voxel_count, popcount) and word indices (k H + y) W + x stay below 2^26 here (2^29
// at the 2^34-voxel limit), so nothing wraps. A tiny triangle in the last voxel and one in
// the first set exactly those.
TEST_P(HardVoxelizers, GridOfMoreThanTwoToThe31Voxels) {
  const ivec3 res{16384, 4100, 32};
  const GridSpec spec = unit_grid(res);
  ASSERT_GT(spec.voxel_count(), int64_t(1) << 31);
  const double d = 1e-3;
  const dvec3 last(16383.5, 4099.5, 31.5), first(0.5);
  const std::vector<dvec3> tiny = {last,  last + dvec3(d, 0, 0),  last + dvec3(0, d, 0),
                                   first, first + dvec3(d, 0, 0), first + dvec3(0, d, 0)};
  const VoxelGrid grid = voxelize_sat(GetParam(), soup_of(tiny), spec).grid.copy_to(Memory::host);
  EXPECT_EQ(grid.popcount(), 2);
  EXPECT_TRUE(grid.get(16383, 4099, 31));
  EXPECT_TRUE(grid.get(0, 0, 0));
  EXPECT_FALSE(grid.get(16383, 4099, 30));
  EXPECT_EQ(grid.words().back(), 1u << 31);
}

INSTANTIATE_TEST_SUITE_P(Backends, HardVoxelizers, ::testing::Values(Backend::cpu, Backend::cuda),
                         BackendName());

}  // namespace
}  // namespace dv::test
