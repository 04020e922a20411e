// The voxelizers on the meshes and grids, per pass with CUDA events (grid clear
// separate, triangle upload separate). sat: the shared bunny scan midpoint-subdivided twice
// (58,784 triangles) and three times (235,136) at 512^3 and 1024^3, the 12-triangle
// axis-aligned cube at 512^3 and 1024^3, two triangles covering a 512^2 x 32 grid against a
// thousand one-voxel triangles. slicemap, atlas and atlas-compute (default 1024^2 atlas): the
// bunny at 512x512x32 and 512^3. Reported time = the kernel work after the upload (sat: small +
// large, as cuda_voxelizer reports its "voxelization GPU time"; the atlas's host-side packing
// is excluded and reported as pack_ms, its atlas update as atlas_update_ms); with_clear_ms adds
// the grid clear (the goal counts it). sat_small/*: the bunny rows with the `small`
// parameter (footprint limit of a triangle voxelized by one thread) swept, to tune it. The
// bandwidth floor (bandwidth_floor.h): copy_GBps is the device-to-device copy bandwidth
// measured once in the run; per modelled pass, PASS_floor_ms = its fewest bytes over that
// bandwidth, and for passes over 100 us PASS_floor_x = PASS_ms / PASS_floor_ms (goal: at most 3).
// Run: build/bin/bench_voxelizer --benchmark_repetitions=5
#include <benchmark/benchmark.h>

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "cuda/device_memory.h"
#include "experiments/bandwidth_floor.h"
#include "experiments/source_paths.h"
#include "render/load/mesh_generators.h"
#include "strategies/voxelizer/atlas_voxelizer.h"
#include "strategies/voxelizer/triangle_soup.h"
#include "strategies/voxelizer/voxel_bounds.h"
#include "strategies/voxelizer/voxelizer.h"

namespace dv {
namespace {

TriangleSoup bench_mesh(const std::string& name) {
  if (name == "bunny2")
    return triangle_soup(make_bunny(test::source_dir() + "/experiments/assets", 2));
  if (name == "bunny3")
    return triangle_soup(make_bunny(test::source_dir() + "/experiments/assets", 3));
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

void run_voxelizer(benchmark::State& state, const char* method, const char* mesh, int res_xy,
                   int res_z, const std::vector<std::string>& params = {}) {
  std::string why;
  if (!cuda_device_available(&why)) return state.SkipWithError(why.c_str());
  const TriangleSoup soup = bench_mesh(mesh);
  Aabb box;
  for (const dvec3& p : soup.corners) box.extend(p);
  const Aabb bounds = std::string(mesh).rfind("bunny", 0) == 0 || std::string(mesh) == "cube"
                          ? cubic_bounds(box, "bench")
                          : Aabb{dvec3(0.0), dvec3(1.0)};
  const GridSpec spec = make_box_grid({res_xy, res_xy, res_z}, bounds, "bench");
  static const double bytes_per_ms = measure_copy_bandwidth();
  auto voxelizer = voxelizer_registry().create(method, StrategyParams::parse(params));
  VoxelizeResult r = voxelizer->voxelize(Backend::cuda, soup, spec);  // warm-up
  std::map<std::string, double> sums;
  double with_clear = 0.0;
  for (auto _ : state) {
    r = voxelizer->voxelize(Backend::cuda, soup, spec);
    double work = 0.0;
    for (const auto& p : r.passes) {
      sums[p.name] += p.milliseconds;
      if (p.name != "clear" && p.name != "upload" && p.name != "pack") work += p.milliseconds;
      if (p.name == "clear") with_clear += p.milliseconds;
    }
    with_clear += work;
    state.SetIterationTime(work / 1e3);
  }
  state.counters["with_clear_ms"] = with_clear / double(state.iterations());
  for (const auto& [name, value] : r.counters.items())
    if (value.is_number()) state.counters[name] = value.get<double>();
  FloorInputs floor{soup.triangle_count(), spec.word_count()};
  for (uint32_t w : r.grid.words()) floor.set_words += w != 0;
  if (std::string(method).rfind("atlas", 0) == 0)
    floor.atlas_texels = int64_t(kDefaultAtlasSide) * kDefaultAtlasSide;
  for (const auto& [name, sum] : sums) {
    const double ms = sum / double(state.iterations());
    state.counters[name + "_ms"] = ms;
    const std::optional<double> bytes = pass_floor_bytes(method, name, floor);
    if (!bytes) continue;
    const double floor_ms = *bytes / bytes_per_ms;
    state.counters[name + "_floor_ms"] = floor_ms;
    if (ms > 0.1) state.counters[name + "_floor_x"] = ms / floor_ms;
  }
  state.counters["copy_GBps"] = bytes_per_ms / 1e6;
  state.counters["triangles"] = double(soup.triangle_count());
  state.SetLabel(cuda_device_name());
}

void sat(benchmark::State& state, const char* mesh, int res_xy, int res_z) {
  run_voxelizer(state, "sat", mesh, res_xy, res_z);
}
void sat_small(benchmark::State& state, const char* mesh, int res_xy, const char* small) {
  run_voxelizer(state, "sat", mesh, res_xy, res_xy, {std::string("small=") + small});
}
void slicemap(benchmark::State& state, const char* mesh, int res_xy, int res_z) {
  run_voxelizer(state, "slicemap", mesh, res_xy, res_z);
}
void atlas(benchmark::State& state, const char* mesh, int res_xy, int res_z) {
  run_voxelizer(state, "atlas", mesh, res_xy, res_z);
}
void atlas_compute(benchmark::State& state, const char* mesh, int res_xy, int res_z) {
  run_voxelizer(state, "atlas-compute", mesh, res_xy, res_z);
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
BENCHMARK_CAPTURE(sat, cube_512, "cube", 512, 512)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(sat, cube_1024, "cube", 1024, 1024)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(sat, two_big_512x32, "two-big", 512, 32)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(sat, thousand_small_512x32, "thousand-small", 512, 32)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

BENCHMARK_CAPTURE(sat_small, bunny2_512_small32, "bunny2", 512, "32")
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(sat_small, bunny2_512_small128, "bunny2", 512, "128")
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(sat_small, bunny2_512_small256, "bunny2", 512, "256")
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(sat_small, bunny2_512_small512, "bunny2", 512, "512")
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(sat_small, bunny2_512_small1024, "bunny2", 512, "1024")
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(sat_small, bunny2_1024_small32, "bunny2", 1024, "32")
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(sat_small, bunny2_1024_small128, "bunny2", 1024, "128")
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(sat_small, bunny2_1024_small256, "bunny2", 1024, "256")
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(sat_small, bunny2_1024_small512, "bunny2", 1024, "512")
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(sat_small, bunny2_1024_small1024, "bunny2", 1024, "1024")
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(sat_small, bunny3_512_small32, "bunny3", 512, "32")
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(sat_small, bunny3_512_small128, "bunny3", 512, "128")
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(sat_small, bunny3_512_small256, "bunny3", 512, "256")
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(sat_small, bunny3_512_small512, "bunny3", 512, "512")
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(sat_small, bunny3_512_small1024, "bunny3", 512, "1024")
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(sat_small, bunny3_1024_small32, "bunny3", 1024, "32")
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(sat_small, bunny3_1024_small128, "bunny3", 1024, "128")
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(sat_small, bunny3_1024_small256, "bunny3", 1024, "256")
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(sat_small, bunny3_1024_small512, "bunny3", 1024, "512")
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(sat_small, bunny3_1024_small1024, "bunny3", 1024, "1024")
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(sat_small, cube_1024_small0, "cube", 1024, "0")
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

BENCHMARK_CAPTURE(slicemap, bunny2_512x32, "bunny2", 512, 32)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(slicemap, bunny2_512, "bunny2", 512, 512)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(atlas, bunny2_512x32, "bunny2", 512, 32)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(atlas, bunny2_512, "bunny2", 512, 512)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(atlas_compute, bunny2_512x32, "bunny2", 512, 32)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(atlas_compute, bunny2_512, "bunny2", 512, 512)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace dv

BENCHMARK_MAIN();
