// The sat voxelizer on the meshes and grids, per pass with CUDA events (grid clear
// separate, triangle upload separate): the shared bunny scan midpoint-subdivided twice (58,784
// triangles) and three times (235,136) at 512^3 and 1024^3, the 12-triangle axis-aligned cube at
// 1024^3, two triangles covering a 512^2 x 32 grid against a thousand one-voxel triangles.
// Reported time = setup + scan + voxelize (the kernel work after the upload), as cuda_voxelizer
// reports its "voxelization GPU time". Run: build/bin/bench_voxelizer --benchmark_repetitions=5
#include <benchmark/benchmark.h>

#include <map>
#include <string>

#include "core/device_memory.h"
#include "generators/mesh_generators.h"
#include "strategies/voxelizer/sat_voxelizer.h"
#include "strategies/voxelizer/triangle_soup.h"
#include "strategies/voxelizer/voxelize_job.h"
#include "tests/support/paths.h"

namespace dv {
namespace {

TriangleSoup bench_mesh(const std::string& name) {
  if (name == "bunny2") return triangle_soup(make_bunny(test::source_dir() + "/assets", 2));
  if (name == "bunny3") return triangle_soup(make_bunny(test::source_dir() + "/assets", 3));
  if (name == "cube") return triangle_soup(make_box({-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5}));
  TriangleSoup soup;
  if (name == "two-big") {  // two triangles spanning the whole x-y extent, tilted through depth
    soup.corners = {{0, 0, 0.1}, {1, 0, 0.2}, {1, 1, 0.9}, {0, 0, 0.1}, {1, 1, 0.9}, {0, 1, 0.8}};
  } else {  // a thousand one-voxel triangles scattered over the grid
    for (int i = 0; i < 1000; ++i) {
      const dvec3 c((i % 31 + 0.3) / 31.0, (i / 31 % 31 + 0.4) / 31.0, (i % 7 + 0.5) / 7.5);
      const double h = 0.3 / 512.0;
      soup.corners.insert(soup.corners.end(), {c, c + dvec3(h, 0, 0), c + dvec3(0, h, 0.0001)});
    }
  }
  return soup;
}

void sat(benchmark::State& state, const char* mesh, int res_xy, int res_z) {
  std::string why;
  if (!cuda_device_available(&why)) return state.SkipWithError(why.c_str());
  const TriangleSoup soup = bench_mesh(mesh);
  Aabb box;
  for (const dvec3& p : soup.corners) box.extend(p);
  const Aabb bounds = std::string(mesh).rfind("bunny", 0) == 0 || std::string(mesh) == "cube"
                          ? cubic_bounds(box, "bench")
                          : Aabb{dvec3(0.0), dvec3(1.0)};
  const GridSpec spec = make_box_grid({res_xy, res_xy, res_z}, bounds, "bench");
  voxelize_sat(Backend::cuda, soup, spec);  // warm-up
  std::map<std::string, double> sums;
  for (auto _ : state) {
    const VoxelizeResult r = voxelize_sat(Backend::cuda, soup, spec);
    double work = 0.0;
    for (const auto& p : r.passes) {
      sums[p.name] += p.milliseconds;
      if (p.name != "clear" && p.name != "upload") work += p.milliseconds;
    }
    state.SetIterationTime(work / 1e3);
  }
  for (const auto& [name, sum] : sums)
    state.counters[name + "_ms"] = sum / double(state.iterations());
  state.counters["triangles"] = double(soup.triangle_count());
  state.SetLabel(cuda_device_name());
}

BENCHMARK_CAPTURE(sat, bunny2_512, "bunny2", 512, 512)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(sat, bunny2_1024, "bunny2", 1024, 1024)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(sat, bunny3_512, "bunny3", 512, 512)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(sat, bunny3_1024, "bunny3", 1024, 1024)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(sat, cube_1024, "cube", 1024, 1024)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(sat, two_big_512x32, "two-big", 512, 32)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(sat, thousand_small_512x32, "thousand-small", 512, 32)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace dv

BENCHMARK_MAIN();
