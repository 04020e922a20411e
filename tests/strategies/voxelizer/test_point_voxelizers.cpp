// The point voxelizers slicemap, atlas and atlas-compute: hand-checked and brute-force sets
// (slicemap: the slice of each covered pixel centre's depth), the axis-aligned cube whose side
// faces the slicemap cannot see (they show up as missing voxels), the atlas packing (disjoint
// cells, texel enumeration, too-small atlases), atlas == atlas-compute bit for bit, whole meshes
// against `exact` (no voxel outside the conservative set; the missing ones reported), the
// registry, and CPU == CUDA (skipped without a GPU).
#include <gtest/gtest.h>

#include <cstdio>
#include <set>

#include "apps/deepvox/voxelize_job.h"
#include "core/error.h"
#include "cuda/device_memory.h"
#include "experiments/source_paths.h"
#include "render/load/mesh_generators.h"
#include "strategies/voxelizer/atlas_device.h"
#include "strategies/voxelizer/atlas_voxelizer.h"
#include "strategies/voxelizer/slicemap_voxelizer.h"
#include "strategies/voxelizer/voxel_metrics.h"
#include "tests/strategies/voxelizer/voxel_meshes.h"
#include "tests/strategies/voxelizer/voxel_test_support.h"

namespace dv {
namespace {

using test::kMeshes;
using test::MeshCase;
using test::soup_of;
using test::VoxelSet;

VoxelSet slicemap_set(const std::vector<dvec3>& corners, ivec3 res) {
  return test::voxels_of(
      voxelize_slicemap(Backend::cpu, soup_of(corners), test::unit_grid(res)).grid);
}

TEST(Slicemap, SingleTriangleSetsTheSliceOfEachCoveredPixelCentre) {
  // x >= 0.2, y >= 0.2, x + y <= 5.1 at z = 2.5: pixel centres (i + .5, j + .5) with i + j <= 4.
  const std::vector<dvec3> tri = {{0.2, 0.2, 2.5}, {4.9, 0.2, 2.5}, {0.2, 4.9, 2.5}};
  VoxelSet expected;
  for (int i = 0; i <= 4; ++i)
    for (int j = 0; i + j <= 4; ++j) expected.insert({i, j, 2});
  EXPECT_EQ(slicemap_set(tri, {8, 8, 32}), expected);
  // The same triangle in the grid's upper face z = 32 lands in the last slice.
  std::vector<dvec3> top = tri;
  for (dvec3& p : top) p.z = 32.0;
  EXPECT_EQ(slicemap_set(top, {8, 8, 32}).size(), 15u);
  EXPECT_TRUE(slicemap_set(top, {8, 8, 32}).count({0, 0, 31}));
}

TEST(Slicemap, TiltedTriangleMatchesPerPixelDepths) {
  // Corners on the 1/8 grid (exact after snapping to 1/256 pixel); no pixel centre on an edge.
  const std::vector<dvec3> tri = {
      {1.125, 0.75, 3.125}, {14.625, 3.25, 40.875}, {4.375, 13.875, 61.5}};
  const ivec3 res{16, 16, 64};
  VoxelSet expected;
  const dvec3 n = glm::cross(tri[1] - tri[0], tri[2] - tri[0]);
  for (int y = 0; y < res.y; ++y)
    for (int x = 0; x < res.x; ++x) {
      const dvec2 p(x + 0.5, y + 0.5);
      double e[3];
      for (int k = 0; k < 3; ++k) {
        const dvec3 &a = tri[size_t(k)], &b = tri[size_t((k + 1) % 3)];
        e[k] = (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
      }
      ASSERT_TRUE(e[0] != 0.0 && e[1] != 0.0 && e[2] != 0.0) << "a centre on an edge";
      if (!((e[0] > 0 && e[1] > 0 && e[2] > 0) || (e[0] < 0 && e[1] < 0 && e[2] < 0))) continue;
      const double z = tri[0].z - (n.x * (p.x - tri[0].x) + n.y * (p.y - tri[0].y)) / n.z;
      expected.insert({x, y, int(z)});
    }
  EXPECT_GT(expected.size(), 60u);
  EXPECT_EQ(slicemap_set(tri, res), expected);
}

TEST(Slicemap, FacesAlongTheViewDirectionAreMissing) {
  // Cube [8, 24]^3 on voxel planes: only the two z faces are seen (16 x 16 pixel centres each,
  // slices 8 and 24); the four side faces are edge-on and set nothing.
  const TriangleSoup soup = triangle_soup(make_box(dvec3(8.0), dvec3(24.0)));
  const GridSpec spec = test::unit_grid({32, 32, 32});
  const VoxelizeResult r = voxelize_slicemap(Backend::cpu, soup, spec);
  VoxelSet expected;
  for (int y = 8; y < 24; ++y)
    for (int x = 8; x < 24; ++x) {
      expected.insert({x, y, 8});
      expected.insert({x, y, 24});
    }
  EXPECT_EQ(test::voxels_of(r.grid), expected);
  EXPECT_EQ(r.counters["zero_area_triangles"].get<int64_t>(), 8);
  const VoxelMetrics m = compare_with_exact(r.grid, voxelize_exact(soup, spec, true));
  EXPECT_EQ(m.filled, 512);
  EXPECT_EQ(m.reference_filled, 18 * 18 * 18 - 14 * 14 * 14);
  EXPECT_EQ(m.missing, m.reference_filled - 512);
  EXPECT_EQ(m.extra, 0);
}

TEST(Atlas, TexelEnumerationCoversEachCellTexelOnce) {
  for (int s : {1, 2, 3, 7, 64, 1000}) {
    std::set<std::pair<int, int>> seen;
    for (int64_t k = 0; k < atlas_cell_texels(s); ++k) {
      int i, j;
      atlas_texel_of(k, i, j);
      ASSERT_TRUE(i >= 0 && j >= 0 && i + j <= s - 1) << s << " " << k;
      seen.insert({i, j});
    }
    EXPECT_EQ(int64_t(seen.size()), atlas_cell_texels(s)) << s;
  }
}

TEST(Atlas, PackingKeepsCellsDisjointAndInside) {
  const TriangleSoup soup = triangle_soup(make_torus(0.35, 0.15, 48, 24));
  const GridSpec spec = make_box_grid({64, 64, 64}, cubic_bounds(soup.bounds(), "torus"));
  for (int side : {64, 256, 1000}) {
    const AtlasLayout layout = pack_atlas(soup, spec, side);
    ASSERT_EQ(int64_t(layout.cells.size()), soup.triangle_count());
    std::vector<uint8_t> used(size_t(side) * side, 0);
    int64_t texels = 0;
    for (const AtlasCell& c : layout.cells) {
      ASSERT_TRUE(c.size >= 1 && c.x >= 0 && c.y >= 0 && c.x + c.size <= side &&
                  c.y + c.size <= side);
      for (int y = c.y; y < c.y + c.size; ++y)
        for (int x = c.x; x < c.x + c.size; ++x) ASSERT_EQ(used[size_t(y) * side + x]++, 0);
      texels += atlas_cell_texels(c.size);
    }
    EXPECT_EQ(layout.valid_texels(), texels);
    EXPECT_GT(layout.texel_size, 0.0);
  }
  try {
    pack_atlas(soup, spec, 10);  // 4608 triangles in 100 texels
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("do not fit"), std::string::npos) << e.what();
  }
  EXPECT_THROW(pack_atlas(soup, spec, 0), InputError);
  EXPECT_THROW(pack_atlas(soup, spec, kMaxAtlasSide + 1), InputError);
}

TEST(Atlas, PointsLieOnTheTriangleAndFillAFlatOne) {
  // One right triangle in the plane z = 5.5 covering 20 x 20 voxels: a fine atlas hits every
  // voxel whose centre it covers, and no voxel off the slice.
  const std::vector<dvec3> tri = {{2.0, 2.0, 5.5}, {22.0, 2.0, 5.5}, {2.0, 22.0, 5.5}};
  const GridSpec spec = test::unit_grid({32, 32, 32});
  const VoxelizeResult r = voxelize_atlas(Backend::cpu, soup_of(tri), spec, 128);
  const VoxelSet set = test::voxels_of(r.grid);
  for (const auto& [x, y, z] : set) {
    EXPECT_EQ(z, 5);
    EXPECT_LE(x + y, 23);
  }
  for (int y = 2; y < 21; ++y)
    for (int x = 2; x + y < 22; ++x) EXPECT_TRUE(set.count({x, y, 5})) << x << " " << y;
  EXPECT_EQ(r.counters["valid_texels"].get<int64_t>(), 128 * 129 / 2);
}

TEST(Atlas, RasterizedAndComputeAgreeBitForBit) {
  const TriangleSoup soup =
      triangle_soup(make_bunny(test::source_dir() + "/experiments/assets", 0));
  const GridSpec spec = make_box_grid({96, 80, 64}, cubic_bounds(soup.bounds(), "bunny"));
  for (int side : {256, 1024, 2000}) {
    const VoxelizeResult a = voxelize_atlas(Backend::cpu, soup, spec, side);
    const VoxelizeResult c = voxelize_atlas_compute(Backend::cpu, soup, spec, side);
    EXPECT_EQ(a.grid.words(), c.grid.words()) << side;
    EXPECT_EQ(a.counters["valid_texels"], c.counters["valid_texels"]);
    EXPECT_GT(a.grid.popcount(), 1000);
    std::vector<std::string> passes;
    for (const VoxelizePass& p : a.passes) passes.push_back(p.name);
    EXPECT_EQ(passes,
              (std::vector<std::string>{"clear", "pack", "upload", "atlas_update", "points"}));
  }
}

const char* const kMethods[] = {"slicemap", "atlas", "atlas-compute"};

class PointVoxelizersVersusExact
    : public ::testing::TestWithParam<std::tuple<MeshCase, const char*>> {};

TEST_P(PointVoxelizersVersusExact, EveryVoxelHoldsASurfacePoint) {
  const auto& [mesh, method] = GetParam();
  const TriangleSoup soup = triangle_soup(mesh.make());
  const Aabb bounds = cubic_bounds(soup.bounds(), mesh.name);
  auto voxelizer = voxelizer_registry().create(method);
  for (const ivec3 res : {ivec3(64, 64, 64), ivec3(128, 128, 32)}) {
    const GridSpec spec = make_box_grid(res, bounds);
    const ExactVoxelization exact = voxelize_exact(soup, spec, true);
    const VoxelizeResult r = voxelizer->voxelize(Backend::cpu, soup, spec);
    const VoxelMetrics m = compare_with_exact(r.grid, exact);
    std::printf(
        "%-13s %-16s %3dx%3dx%3d  exact %7lld  filled %7lld  missing %7lld (outside band %lld)"
        "  extra %lld (outside band %lld)\n",
        method, mesh.name, res.x, res.y, res.z, (long long)m.reference_filled, (long long)m.filled,
        (long long)m.missing, (long long)m.missing_outside_band, (long long)m.extra,
        (long long)m.extra_outside_band);
    EXPECT_EQ(m.filled, r.grid.popcount());
    EXPECT_EQ(m.missing, m.reference_filled - (m.filled - m.extra));
    // A point method's voxel holds a surface point, so its closed box meets the surface. The
    // slicemap's depths come from pixel centres that may lie up to 1/512 pixel outside a
    // triangle (1/256-pixel snapping), so a few of its voxels may touch only that neighbourhood.
    if (std::string(method) == "slicemap")
      EXPECT_LE(m.extra_outside_band, m.filled / 1000);
    else
      EXPECT_EQ(m.extra_outside_band, 0);
    if (std::string(mesh.name) == "subdivided_quad" && std::string(method) == "slicemap") {
      // The quad lies in a plane containing the view direction: seen edge-on, nothing is set.
      EXPECT_EQ(m.filled, 0);
      EXPECT_EQ(m.missing, m.reference_filled);
      EXPECT_EQ(r.counters["zero_area_triangles"].get<int64_t>(), soup.triangle_count());
    } else {
      EXPECT_GT(m.filled, m.reference_filled / 4);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Meshes, PointVoxelizersVersusExact,
                         ::testing::Combine(::testing::ValuesIn(kMeshes),
                                            ::testing::ValuesIn(kMethods)),
                         [](const auto& info) {
                           std::string method = std::get<1>(info.param);
                           for (char& c : method)
                             if (c == '-') c = '_';
                           return std::string(std::get<0>(info.param).name) + "_" + method;
                         });

TEST(PointVoxelizers, RegistryParametersAndErrors) {
  for (const char* name : kMethods) {
    auto v = voxelizer_registry().create(name);
    EXPECT_EQ(v->name(), name);
    EXPECT_TRUE(v->supports(Backend::cpu));
  }
  EXPECT_EQ(voxelizer_registry().create("atlas")->params()["atlas"].get<int>(), kDefaultAtlasSide);
  auto fine = voxelizer_registry().create("ATLAS-compute", StrategyParams::parse({"atlas=64"}));
  EXPECT_EQ(fine->params()["atlas"].get<int>(), 64);
  EXPECT_THROW(voxelizer_registry().create("atlas", StrategyParams::parse({"atlas=0"})),
               InputError);
  EXPECT_THROW(voxelizer_registry().create("atlas", StrategyParams::parse({"atlas=99999"})),
               InputError);
  EXPECT_THROW(voxelizer_registry().create("slicemap", StrategyParams::parse({"atlas=64"})),
               InputError);
  // Empty input: a cleared grid, no passes beyond what ran.
  for (const char* name : kMethods)
    EXPECT_EQ(voxelizer_registry()
                  .create(name)
                  ->voxelize(Backend::cpu, TriangleSoup{}, test::unit_grid({8, 8, 32}))
                  .grid.popcount(),
              0);
}

TEST(PointVoxelizers, GlBackendWithoutGlIsAnInputError) {
  // This test program does not link the GL library: its GL registry is empty.
  VoxelizeJob job;
  job.input = test::source_dir() + "/experiments/scenes/none.json";
  job.method = "slicemap";
  job.backend = "gl";
  try {
    run_voxelize_job(job);
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--backend"), std::string::npos) << e.what();
  }
  EXPECT_EQ(voxelize_job_backend(job), Backend::cpu);
}

class PointVoxelizersCpuCuda : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string why;
    if (!cuda_device_available(&why)) GTEST_SKIP() << "CPU/CUDA parity needs a GPU: " << why;
  }
};

TEST_F(PointVoxelizersCpuCuda, IdenticalGrids) {
  const TriangleSoup soup = triangle_soup(test::bunny_mesh());
  const Aabb bounds = cubic_bounds(soup.bounds(), "bunny");
  for (const char* name : kMethods) {
    auto v = voxelizer_registry().create(name);
    for (const ivec3 res : {ivec3(64, 64, 64), ivec3(256, 256, 32), ivec3(100, 37, 1024)}) {
      const GridSpec spec = make_box_grid(res, bounds);
      const VoxelizeResult c = v->voxelize(Backend::cpu, soup, spec);
      const VoxelizeResult g = v->voxelize(Backend::cuda, soup, spec);
      EXPECT_EQ(g.grid.memory(), Memory::device);
      EXPECT_EQ(c.grid.words(), g.grid.words()) << name << " " << res.x << "x" << res.y;
      EXPECT_EQ(c.counters, g.counters) << name;
      EXPECT_GT(c.grid.popcount(), 0) << name;
    }
  }
}

}  // namespace
}  // namespace dv
