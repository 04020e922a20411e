// The OpenGL slicemap against the CPU one (the shared tile rasterizer) on the same input:
// equal bit for bit where the driver rasterizes with our rule, otherwise at most 0.1 % of the
// voxels differ and the differences are printed. Meshes at several grids, depths 32 to 1024,
// odd widths; the cube's side faces missing in both; `deepvox voxelize --backend gl` through
// the registry. Skips with the reason where no headless OpenGL 4.5 context can be had.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "core/error.h"

#include "apps/deepvox/voxelize_job.h"
#include "experiments/source_paths.h"
#include "gl/egl_context.h"
#include "gl/gl_slicemap.h"
#include "gl/gl_voxelizers.h"
#include "render/load/mesh_generators.h"
#include "strategies/voxelizer/slicemap_voxelizer.h"
#include "tests/gl/gl_test_support.h"

namespace dv {
namespace {

class GlSlicemap : public test::GlContextTest {};

using test::count_differences;

TEST_F(GlSlicemap, AgreesWithTheSharedRasterizer) {
  std::printf("GL renderer: %s\n", context_->renderer().c_str());
  const std::vector<std::pair<const char*, TriangleSoup>> meshes = {
      {"bunny", triangle_soup(make_bunny(test::source_dir() + "/experiments/assets", 0))},
      {"icosphere", triangle_soup(make_icosphere(0.5, 3))},
      {"torus", triangle_soup(make_torus(0.35, 0.15, 48, 24))}};
  int64_t total_differ = 0, total_filled = 0;
  for (const auto& [name, soup] : meshes) {
    const Aabb bounds = cubic_bounds(soup.bounds(), name);
    for (const ivec3 res : {ivec3(64, 64, 32), ivec3(128, 128, 128), ivec3(256, 256, 1024),
                            ivec3(100, 37, 96), ivec3(512, 512, 32)}) {
      const GridSpec spec = make_box_grid(res, bounds);
      const VoxelizeResult cpu = voxelize_slicemap(Backend::cpu, soup, spec);
      const VoxelizeResult gl = gl::voxelize_slicemap_gl(soup, spec);
      EXPECT_EQ(gl.grid.memory(), Memory::host);
      const std::string label = std::string(name) + " " + std::to_string(res.x) + "x" +
                                std::to_string(res.y) + "x" + std::to_string(res.z);
      const int64_t filled = cpu.grid.popcount();
      const int64_t differ = count_differences(cpu.grid, gl.grid, label);
      std::printf("%-24s cpu %8lld  gl %8lld  differing %lld (%.4f %%)\n", label.c_str(),
                  (long long)filled, (long long)gl.grid.popcount(), (long long)differ,
                  100.0 * double(differ) / double(std::max<int64_t>(filled, 1)));
      EXPECT_GT(filled, 100) << label;
      EXPECT_LE(differ * 1000, filled) << label << ": more than 0.1 % of the voxels differ";
      total_differ += differ;
      total_filled += filled;
    }
  }
  RecordProperty("differing_voxels", std::to_string(total_differ));
  RecordProperty("cpu_voxels", std::to_string(total_filled));
}

TEST_F(GlSlicemap, CubeSideFacesAreMissingToo) {
  const TriangleSoup soup = triangle_soup(make_box(dvec3(8.0), dvec3(24.0)));
  const GridSpec spec = make_box_grid({32, 32, 32}, Aabb{dvec3(0.0), dvec3(32.0)});
  const VoxelizeResult gl = gl::voxelize_slicemap_gl(soup, spec);
  const VoxelizeResult cpu = voxelize_slicemap(Backend::cpu, soup, spec);
  EXPECT_EQ(gl.grid.popcount(), 2 * 16 * 16);
  EXPECT_EQ(gl.grid.words(), cpu.grid.words());
}

TEST_F(GlSlicemap, LimitsAndDegenerateInput) {
  const GridSpec spec = make_box_grid({16, 16, 64}, Aabb{dvec3(0.0), dvec3(16.0, 16.0, 64.0)});
  EXPECT_EQ(gl::voxelize_slicemap_gl(TriangleSoup{}, spec).grid.popcount(), 0);
  TriangleSoup bad;
  bad.add({1.0, 1.0, 1.0}, {1e300, 1.0, 1.0}, {1.0, 1e300, 1.0});  // too big for float
  bad.add({1.2, 1.2, 40.5}, {9.7, 1.2, 40.5}, {1.2, 9.7, 40.5});
  const VoxelizeResult r = gl::voxelize_slicemap_gl(bad, spec);
  EXPECT_EQ(r.counters["skipped_triangles"].get<int64_t>(), 1);
  TriangleSoup good;
  good.corners.assign(bad.corners.begin() + 3, bad.corners.end());
  EXPECT_EQ(r.grid.words(), voxelize_slicemap(Backend::cpu, good, spec).grid.words());
}

TEST_F(GlSlicemap, VoxelizeCommandRunsItWithBackendGl) {
  gl::install_gl_voxelizers();
  VoxelizeJob job;
  job.input = test::source_dir() + "/experiments/assets/meshes/stanford-bunny-lowres.obj";
  job.method = "slicemap";
  job.backend = "gl";
  job.res = "64x64x64";
  job.compare_exact = true;
  const nlohmann::json stats = run_voxelize_job(job);
  EXPECT_EQ(stats["backend"], "gl");
  EXPECT_EQ(stats["method"], "slicemap");
  EXPECT_GT(stats["filled"].get<int64_t>(), 1000);
  EXPECT_GT(stats["exact"]["metrics"]["missing"].get<int64_t>(), 0);
  job.method = "sat";  // no GL implementation
  EXPECT_THROW(run_voxelize_job(job), InputError);
}

}  // namespace
}  // namespace dv
