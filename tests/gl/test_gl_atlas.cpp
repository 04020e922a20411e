// The OpenGL atlas against the CPU one (the shared tile rasterizer, double-precision points) on
// the same atlas: the driver covers the same texels (the packing keeps texel centres off the
// edges), so the grids differ only where a texel's point lies within float rounding of a voxel
// face; every differing voxel must be such a one, and at most 0.1 % of the voxels may differ.
// Meshes at several box grids (depth 32 to 1024, odd sizes and atlas sides), a perspective
// light grid, bad input, and `deepvox voxelize --method atlas --backend gl` through the registry.
// Skips with the reason where no headless OpenGL 4.5 context can be had.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <unordered_set>

#include "apps/deepvox/voxelize_job.h"
#include "core/error.h"
#include "engine/raster/light_faces.h"
#include "experiments/source_paths.h"
#include "gl/gl_atlas.h"
#include "gl/gl_voxelizers.h"
#include "render/load/mesh_generators.h"
#include "strategies/voxelizer/atlas_device.h"
#include "strategies/voxelizer/atlas_voxelizer.h"
#include "strategies/voxelizer/frustum_grid.h"
#include "tests/gl/gl_test_support.h"
#include "tests/support/light_face_cases.h"

namespace dv {
namespace {

class GlAtlas : public test::GlContextTest {};

// How far float interpolation may move a texel's grid point, in voxels.
constexpr double kRounding = 1e-3;

// The voxels that the points of texels within kRounding of a voxel face can land in when moved
// by up to kRounding along each axis: the only places where the two grids may differ.
std::unordered_set<int64_t> borderline_voxels(const TriangleSoup& soup, const GridSpec& spec,
                                              int side) {
  const AtlasLayout layout = pack_atlas(soup, spec, side);
  const GridTransform to_grid = grid_transform(spec);
  std::unordered_set<int64_t> out;
  for (size_t t = 0; t < layout.cells.size(); ++t) {
    const AtlasCell& cell = layout.cells[t];
    for (int64_t local = 0; local < atlas_cell_texels(cell.size); ++local) {
      int i, j;
      atlas_texel_of(local, i, j);
      const dvec3 g = to_grid.apply(atlas_point(&soup.corners[3 * t], cell, i, j));
      bool near_face = false;
      for (int a = 0; a < 3; ++a)
        near_face = near_face || std::abs(g[a] - std::round(g[a])) < kRounding;
      if (!near_face) continue;
      for (int c = 0; c < 8; ++c) {
        const dvec3 moved = g + kRounding * dvec3(c & 1 ? 1 : -1, c & 2 ? 1 : -1, c & 4 ? 1 : -1);
        ivec3 v;
        if (point_voxel_index(moved, spec.res, v))
          out.insert((int64_t(v.z) * spec.res.y + v.y) * spec.res.x + v.x);
      }
    }
  }
  return out;
}

// Differing voxels that no texel near a voxel face explains.
int64_t unexplained_differences(const VoxelGrid& cpu, const VoxelGrid& gl,
                                const std::unordered_set<int64_t>& borderline) {
  const ivec3 r = cpu.spec().res;
  const VoxelGridView a = cpu.view(), b = gl.view();
  int64_t unexplained = 0;
  for (int z = 0; z < r.z; ++z)
    for (int y = 0; y < r.y; ++y)
      for (int x = 0; x < r.x; ++x)
        if (a.get(x, y, z) != b.get(x, y, z) && !borderline.count((int64_t(z) * r.y + y) * r.x + x))
          ++unexplained;
  return unexplained;
}

// Compares GL and CPU on one input and prints the counts; returns the differing voxels.
int64_t expect_agreement(const TriangleSoup& soup, const GridSpec& spec, int side,
                         const std::string& label) {
  const VoxelizeResult cpu = voxelize_atlas(Backend::cpu, soup, spec, side);
  const VoxelizeResult gl = gl::voxelize_atlas_gl(soup, spec, side);
  EXPECT_EQ(gl.grid.memory(), Memory::host);
  EXPECT_EQ(gl.counters.at("valid_texels"), cpu.counters.at("valid_texels")) << label;
  const int64_t filled = cpu.grid.popcount();
  const int64_t differ = test::count_differences(cpu.grid, gl.grid, label);
  const int64_t unexplained =
      differ ? unexplained_differences(cpu.grid, gl.grid, borderline_voxels(soup, spec, side)) : 0;
  std::printf("%-32s cpu %8lld  gl %8lld  differing %lld (%.4f %%), unexplained %lld\n",
              label.c_str(), (long long)filled, (long long)gl.grid.popcount(), (long long)differ,
              100.0 * double(differ) / double(std::max<int64_t>(filled, 1)),
              (long long)unexplained);
  EXPECT_GT(filled, 100) << label;
  EXPECT_LE(differ * 1000, filled) << label << ": more than 0.1 % of the voxels differ";
  EXPECT_EQ(unexplained, 0) << label << ": differences away from voxel faces";
  return differ;
}

TEST_F(GlAtlas, AgreesWithTheCpuAtlas) {
  std::printf("GL renderer: %s\n", context_->renderer().c_str());
  const std::vector<std::pair<const char*, TriangleSoup>> meshes = {
      {"bunny", triangle_soup(make_bunny(test::source_dir() + "/experiments/assets", 0))},
      {"icosphere", triangle_soup(make_icosphere(0.5, 3))},
      {"torus", triangle_soup(make_torus(0.35, 0.15, 48, 24))}};
  int64_t total_differ = 0;
  for (const auto& [name, soup] : meshes) {
    const Aabb bounds = cubic_bounds(soup.bounds(), name);
    for (const ivec3 res :
         {ivec3(64, 64, 32), ivec3(128, 128, 128), ivec3(256, 256, 1024), ivec3(100, 37, 96)}) {
      const int side = res.x == 100 ? 777 : 1024;
      const std::string label = std::string(name) + " " + std::to_string(res.x) + "x" +
                                std::to_string(res.y) + "x" + std::to_string(res.z) + " atlas " +
                                std::to_string(side);
      total_differ += expect_agreement(soup, make_box_grid(res, bounds), side, label);
    }
  }
  RecordProperty("differing_voxels", std::to_string(total_differ));
}

TEST_F(GlAtlas, AgreesOnAPerspectiveLightGrid) {
  const ShadowFace face = test::spot_face(96);
  dmat4 m(1.0);
  m[3] = dvec4(0.2, 1.0, -0.1, 1.0);
  const TriangleSoup ball = triangle_soup(make_icosphere(0.7, 3), m);
  const GridSpec spec = make_light_grid(face, 96, 64, ball.bounds());
  ASSERT_EQ(spec.kind, GridKind::perspective);
  expect_agreement(ball, spec, 512, "icosphere spot 96x96x64 atlas 512");
}

TEST_F(GlAtlas, BadInputAndEmptySoup) {
  const GridSpec spec = make_box_grid({16, 16, 64}, Aabb{dvec3(0.0), dvec3(16.0, 16.0, 64.0)});
  EXPECT_EQ(gl::voxelize_atlas_gl(TriangleSoup{}, spec, 64).grid.popcount(), 0);
  const TriangleSoup ball = triangle_soup(make_icosphere(4.0, 3));
  EXPECT_THROW(gl::voxelize_atlas_gl(ball, spec, 0), InputError);
  EXPECT_THROW(gl::voxelize_atlas_gl(ball, spec, kMaxAtlasSide + 1), InputError);
  EXPECT_THROW(gl::voxelize_atlas_gl(ball, spec, 8), InputError);  // 1280 triangles, 64 texels
  gl::install_gl_voxelizers();
  EXPECT_THROW(gl_voxelizer_registry().create("atlas", StrategyParams::parse({"atlas=0"})),
               InputError);
}

TEST_F(GlAtlas, VoxelizeCommandRunsItWithBackendGl) {
  gl::install_gl_voxelizers();
  VoxelizeJob job;
  job.input = test::source_dir() + "/experiments/assets/meshes/stanford-bunny-lowres.obj";
  job.method = "atlas";
  job.backend = "gl";
  job.res = "64x64x64";
  job.params = {"atlas=512"};
  const nlohmann::json stats = run_voxelize_job(job);
  EXPECT_EQ(stats["backend"], "gl");
  EXPECT_EQ(stats["method"], "atlas");
  EXPECT_GT(stats["filled"].get<int64_t>(), 1000);
  std::printf("voxelize --method atlas --backend gl: %s\n", stats.dump().c_str());
}

}  // namespace
}  // namespace dv
