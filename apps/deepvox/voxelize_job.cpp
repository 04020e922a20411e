// The voxelize command's work (see voxelize_job.h).
#include "apps/deepvox/voxelize_job.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "core/wall_phases.h"
#include "cuda/execute.h"
#include "cuda/kernel_timing.h"
#include "render/io/binvox.h"
#include "render/io/output_path.h"
#include "render/io/vdb_io.h"
#include "render/load/scene_loader.h"
#include "strategies/voxelizer/exact_voxelizer.h"
#include "strategies/voxelizer/voxel_metrics.h"
#include "strategies/voxelizer/voxelizer.h"

namespace dv {

namespace {

nlohmann::json vec(const dvec3& v) {
  return {v.x, v.y, v.z};
}

bool writes_vdb(const VoxelizeJob& job) {
  return std::filesystem::path(job.out).extension() == ".vdb";
}

void write_json(const std::string& path, const nlohmann::json& j) {
  std::ofstream out(path);
  if (!out) throw InputError(path, "cannot write stats file");
  out << j.dump(2) << "\n";
  if (!out) throw InputError(path, "writing the stats file failed");
}

}  // namespace

bool voxelize_job_uses_gl(const VoxelizeJob& job) {
  return job.backend == "gl";
}

Backend voxelize_job_backend(const VoxelizeJob& job) {
  if (voxelize_job_uses_gl(job)) return Backend::cpu;
  return job.backend.empty() ? default_backend() : parse_backend(job.backend);
}

nlohmann::json run_voxelize_job(const VoxelizeJob& job, const RunMetadataSource& meta) {
  if (!job.out.empty()) {  // before any work
    check_output_path(job.out, {".binvox", ".vdb"}, "voxel grid");
    if (writes_vdb(job)) require_vdb_support(job.out);
  }
  if (!job.stats.empty()) check_output_path(job.stats, {".json"}, "stats JSON");
  const bool gl = voxelize_job_uses_gl(job);
  const Registry<Voxelizer>& registry = gl ? gl_voxelizer_registry() : voxelizer_registry();
  if (gl && registry.names().empty())
    throw InputError("--backend",
                     "gl: this program has no OpenGL voxelizers (built without "
                     "DEEPVOX_GL, or EGL/OpenGL missing at build time)");
  auto method = registry.create(job.method, StrategyParams::parse(job.params));
  const ivec3 res = parse_voxel_resolution(job.res);
  const Aabb given = job.bounds.empty() ? Aabb{} : parse_voxel_bounds(job.bounds);

  // The input loads while the CUDA driver starts in the background (main.cpp); the backend
  // query below waits for the driver. The model alone: no staged ground plane to voxelize, and
  // no staged lights (nothing is lit).
  const Scene scene = load_scene(job.input, {.ground = GroundPlane::off, .lights = false});
  const TriangleSoup soup = triangle_soup(scene);
  mark_wall_phase("input loaded");
  const Backend backend = voxelize_job_backend(job);
  if (!method->supports(backend))
    throw InputError("--backend", "voxelizer '" + method->name() + "' does not run on " +
                                      to_string(backend) + " in this build");
  require_backend(backend);
  const Aabb bounds = job.bounds.empty() ? cubic_bounds(soup.bounds(), job.input) : given;
  const GridSpec spec = make_box_grid(res, bounds, "--bounds");

  VoxelizeResult result = method->voxelize(backend, soup, spec);
  mark_wall_phase("voxelized");
  // One read-back serves the count, the comparison and the file (each would copy a device grid).
  if (result.grid.memory() == Memory::device) result.grid = result.grid.copy_to(Memory::host);
  const int64_t filled = result.grid.popcount();
  nlohmann::json stats = {{"input", job.input},
                          {"method", method->name()},
                          {"params", method->params()},
                          {"backend", gl ? "gl" : to_string(backend)},
                          {"res", {res.x, res.y, res.z}},
                          {"bounds", {{"min", vec(bounds.lo)}, {"max", vec(bounds.hi)}}},
                          {"voxel_size", vec(spec.voxel_size())},
                          {"triangles", soup.triangle_count()},
                          {"filled", filled},
                          {"passes", result.passes_json()},
                          {"total_ms", result.total_milliseconds()},
                          {"counters", result.counters}};
  if (meta) stats["meta"] = meta(backend);
  if (kernel_timing_enabled()) stats["kernels"] = kernel_timings_json();
  if (job.compare_exact) {
    const ExactVoxelization exact = voxelize_exact(soup, spec, true);
    stats["exact"] = {{"ms", exact.milliseconds},
                      {"metrics", compare_with_exact(result.grid, exact).to_json()}};
  }
  if (!job.out.empty() && writes_vdb(job)) {
    write_vdb_occupancy(job.out, result.grid);
    mark_wall_phase("vdb written");
    stats["vdb"] = {{"path", job.out},
                    {"grid", "density"},
                    {"first_voxel_centre", vec(bounds.lo + 0.5 * spec.voxel_size())}};
  } else if (!job.out.empty()) {
    write_binvox(job.out, result.grid);
    mark_wall_phase("binvox written");
    const int max_dim = std::max({res.x, res.y, res.z});
    stats["binvox"] = {
        {"path", job.out}, {"translate", vec(bounds.lo)}, {"scale", spec.voxel_size().x * max_dim}};
  }
  stats["wall_ms"] = wall_phases_json();
  if (!job.stats.empty()) write_json(job.stats, stats);
  return stats;
}

}  // namespace dv
