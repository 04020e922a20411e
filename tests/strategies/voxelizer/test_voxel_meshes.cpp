// sat against the exact reference on whole meshes (icosphere, torus, the shared bunny, a
// subdivided quad lying on a voxel plane) at 64^3 and 128x128x32: no voxel missing outside
// the borderline band; extra voxels are reported. The work split by triangle footprint does
// not change the grid. Then CPU == CUDA grids, bit for bit (skipped without a GPU).
#include <gtest/gtest.h>

#include <cstdio>

#include "apps/deepvox/voxelize_job.h"
#include "cuda/device_memory.h"
#include "experiments/source_paths.h"
#include "render/load/mesh_generators.h"
#include "strategies/voxelizer/sat_device.h"
#include "strategies/voxelizer/sat_voxelizer.h"
#include "strategies/voxelizer/voxel_metrics.h"
#include "tests/strategies/voxelizer/voxel_meshes.h"

namespace dv {
namespace {

using test::kMeshes;
using test::MeshCase;

TriangleMesh cube() {
  return make_box(dvec3(-0.5), dvec3(0.5));
}

class SatVersusExact : public ::testing::TestWithParam<MeshCase> {};

TEST_P(SatVersusExact, NothingMissingOutsideTheBand) {
  const TriangleSoup soup = triangle_soup(GetParam().make());
  const Aabb bounds = cubic_bounds(soup.bounds(), GetParam().name);
  for (const ivec3 res : {ivec3(64, 64, 64), ivec3(128, 128, 32)}) {
    const GridSpec spec = make_box_grid(res, bounds);
    const ExactVoxelization exact = voxelize_exact(soup, spec, true);
    const VoxelizeResult sat = voxelize_sat(Backend::cpu, soup, spec);
    const VoxelMetrics m = compare_with_exact(sat.grid, exact);
    std::printf(
        "%-16s %3dx%3dx%3d  triangles %6lld  exact %7lld  sat %7lld  missing %lld "
        "(outside band %lld)  extra %lld (outside band %lld)  band %lld\n",
        GetParam().name, res.x, res.y, res.z, (long long)soup.triangle_count(),
        (long long)m.reference_filled, (long long)m.filled, (long long)m.missing,
        (long long)m.missing_outside_band, (long long)m.extra, (long long)m.extra_outside_band,
        (long long)m.borderline);
    EXPECT_GT(m.reference_filled, 1000);
    EXPECT_EQ(m.missing_outside_band, 0);
    EXPECT_EQ(m.extra_outside_band, 0);
    // Both compute in double: any disagreement is a rounding tie inside the band.
    EXPECT_LE(m.missing + m.extra, m.borderline);
    EXPECT_EQ(m.filled, sat.grid.popcount());
  }
}

INSTANTIATE_TEST_SUITE_P(Meshes, SatVersusExact, ::testing::ValuesIn(kMeshes),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(SatVersusExact, QuadOnAVoxelPlaneSetsBothLayers) {
  // The quad lies in y = 0, the middle plane of its cubic box: grid y = 32 exactly, so the
  // closed voxel boxes of both layers y = 31 and y = 32 meet it.
  const TriangleSoup soup = triangle_soup(test::quad_mesh());
  const GridSpec spec = make_box_grid({64, 64, 64}, cubic_bounds(soup.bounds(), "quad"));
  const VoxelizeResult sat = voxelize_sat(Backend::cpu, soup, spec);
  EXPECT_EQ(sat.grid.popcount(), 2 * 64 * 64);
  EXPECT_TRUE(sat.grid.get(0, 31, 0) && sat.grid.get(63, 32, 63));
}

// The bunny with a cube around it (its 12 triangles span whole faces of the grid) and two
// degenerate triangles: small and large triangles in one soup.
TriangleSoup mixed_sizes_soup() {
  TriangleSoup soup = triangle_soup(test::bunny_mesh());
  const Aabb box = soup.bounds();
  const TriangleSoup shell = triangle_soup(make_box(box.lo, box.hi));
  soup.corners.insert(soup.corners.end(), shell.corners.begin(), shell.corners.end());
  soup.add(box.lo, box.center(), box.lo);
  soup.add(box.center(), box.center(), box.center());
  return soup;
}

// Classification by footprint (small triangles whole on one thread, large ones column by
// column from the large list, in one list or in batches) never changes the grid or the work
// counted: every route against a mixed split (at most 64 columns on one thread: the cube's
// faces large, the bunny's triangles small at both grids).
TEST(SatWorkSplit, GridDoesNotDependOnTheSplit) {
  const TriangleSoup soup = mixed_sizes_soup();
  const int64_t triangles = soup.triangle_count();
  const Aabb bounds = cubic_bounds(soup.bounds(), "mixed");
  for (const ivec3 res : {ivec3(64, 64, 64), ivec3(100, 37, 96)}) {
    const GridSpec spec = make_box_grid(res, bounds);
    const VoxelizeResult split = voxelize_sat(Backend::cpu, soup, spec, 64);
    const int64_t large = split.counters["large_triangles"].get<int64_t>();
    EXPECT_GE(large, 12) << "the cube's faces are large";
    EXPECT_LT(large, triangles / 10) << "the bunny's triangles are small";
    const VoxelizeResult all_large = voxelize_sat(Backend::cpu, soup, spec, 0);
    const VoxelizeResult all_small = voxelize_sat(Backend::cpu, soup, spec, kSatMaxSmallItems);
    const VoxelizeResult batched = voxelize_sat(Backend::cpu, soup, spec, 0, 7);
    // Triangles with work: all but faces of the cube that round to just outside the grid.
    const GridTransform to_grid = grid_transform(spec);
    int64_t with_work = 0;
    for (int64_t i = 0; i < triangles; ++i) {
      SatTriangle t;
      with_work +=
          sat_setup(to_grid.apply(soup.corners[3 * i]), to_grid.apply(soup.corners[3 * i + 1]),
                    to_grid.apply(soup.corners[3 * i + 2]), spec.res, t) &&
          t.work_items > 0;
    }
    EXPECT_GE(with_work, triangles - 2);
    EXPECT_EQ(all_large.counters["large_triangles"].get<int64_t>(), with_work);
    EXPECT_EQ(batched.counters["large_triangles"].get<int64_t>(), with_work);
    EXPECT_EQ(all_small.counters["large_triangles"].get<int64_t>(), 0);
    EXPECT_EQ(split.counters["degenerate_triangles"].get<int64_t>(), 2);
    const std::vector<uint32_t> words = split.grid.words();
    EXPECT_GT(split.grid.popcount(), 1000);
    for (const VoxelizeResult* other : {&all_large, &all_small, &batched}) {
      EXPECT_EQ(other->grid.words(), words) << res.x << "x" << res.y << "x" << res.z;
      EXPECT_EQ(other->counters["work_items"], split.counters["work_items"]);
      EXPECT_EQ(other->counters["degenerate_triangles"], split.counters["degenerate_triangles"]);
    }
  }
  EXPECT_THROW(voxelize_sat(Backend::cpu, soup, make_box_grid({8, 8, 32}, bounds), -1), InputError);
}

class CpuCudaParity : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string why;
    if (!cuda_device_available(&why)) GTEST_SKIP() << "CPU/CUDA parity needs a GPU: " << why;
  }
};

TEST_F(CpuCudaParity, IdenticalGrids) {
  std::vector<std::pair<const char*, TriangleSoup>> cases;
  cases.emplace_back("bunny", triangle_soup(test::bunny_mesh()));
  cases.emplace_back("cube", triangle_soup(cube()));
  cases.emplace_back("quad", triangle_soup(test::quad_mesh()));
  TriangleSoup degenerate;
  degenerate.add({0.1, 0.2, 0.3}, {-0.4, 0.3, -0.2}, {0.1, 0.2, 0.3});
  degenerate.add({0.25, 0.25, 0.25}, {0.25, 0.25, 0.25}, {0.25, 0.25, 0.25});
  cases.emplace_back("degenerate", degenerate);
  cases.emplace_back("mixed sizes", mixed_sizes_soup());
  for (const auto& [name, soup] : cases) {
    const Aabb bounds = cubic_bounds(triangle_soup(cube()).bounds(), name);
    for (const ivec3 res : {ivec3(64, 64, 64), ivec3(256, 256, 32), ivec3(100, 37, 96)}) {
      const GridSpec spec = make_box_grid(res, bounds);
      const VoxelizeResult c = voxelize_sat(Backend::cpu, soup, spec);
      const VoxelizeResult g = voxelize_sat(Backend::cuda, soup, spec);
      EXPECT_EQ(g.grid.memory(), Memory::device);
      EXPECT_EQ(c.grid.words(), g.grid.words()) << name << " " << res.x << "x" << res.y;
      EXPECT_EQ(c.counters, g.counters) << name;
      EXPECT_GT(c.grid.popcount(), 0) << name;
      // Every triangle through the large list on the device, in batches of 5: the same grid.
      const VoxelizeResult columns = voxelize_sat(Backend::cuda, soup, spec, 0, 5);
      EXPECT_EQ(c.grid.words(), columns.grid.words()) << name << " " << res.x << "x" << res.y;
      EXPECT_EQ(c.counters["work_items"], columns.counters["work_items"]) << name;
    }
  }
}

TEST_F(CpuCudaParity, MipOnTheDevice) {
  const TriangleSoup soup = triangle_soup(test::bunny_mesh());
  const GridSpec spec = make_box_grid({77, 51, 64}, cubic_bounds(soup.bounds(), "bunny"));
  const VoxelizeResult c = voxelize_sat(Backend::cpu, soup, spec);
  const VoxelizeResult g = voxelize_sat(Backend::cuda, soup, spec);
  const std::vector<VoxelGrid> host = mip_chain(c.grid), device = mip_chain(g.grid);
  ASSERT_EQ(host.size(), device.size());
  for (size_t i = 0; i < host.size(); ++i) EXPECT_EQ(host[i].words(), device[i].words()) << i;
}

}  // namespace
}  // namespace dv
