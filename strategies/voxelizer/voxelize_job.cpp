// The voxelize command's work (see voxelize_job.h).
#include "strategies/voxelizer/voxelize_job.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>

#include "core/error.h"
#include "core/execute.h"
#include "io/binvox.h"
#include "io/output_path.h"
#include "io/scene_loader.h"
#include "strategies/voxelizer/exact_voxelizer.h"
#include "strategies/voxelizer/voxel_metrics.h"
#include "strategies/voxelizer/voxelizer.h"

namespace dv {

namespace {

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  size_t start = 0;
  for (;;) {
    const size_t end = text.find(separator, start);
    parts.push_back(text.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) return parts;
    start = end + 1;
  }
}

nlohmann::json vec(const dvec3& v) {
  return {v.x, v.y, v.z};
}

void write_json(const std::string& path, const nlohmann::json& j) {
  std::ofstream out(path);
  if (!out) throw InputError(path, "cannot write stats file");
  out << j.dump(2) << "\n";
  if (!out) throw InputError(path, "writing the stats file failed");
}

}  // namespace

ivec3 parse_voxel_resolution(const std::string& text, const std::string& where) {
  std::vector<std::string> parts = split(text, 'x');
  if (parts.size() == 1) parts = {parts[0], parts[0], parts[0]};
  if (parts.size() != 3)
    throw InputError(where, "expected WxHxD (e.g. 512x512x32), got '" + text + "'");
  ivec3 res;
  for (int a = 0; a < 3; ++a) {
    const std::string& p = parts[size_t(a)];
    if (p.empty() || p.size() > 9 ||
        !std::all_of(p.begin(), p.end(), [](char c) { return c >= '0' && c <= '9'; }))
      throw InputError(where, "expected WxHxD with positive whole numbers, got '" + text + "'");
    res[a] = std::atoi(p.c_str());
  }
  GridSpec probe;
  probe.res = res;
  probe.bounds = {dvec3(0.0), dvec3(1.0)};
  validate_grid_spec(probe, where);
  return res;
}

Aabb parse_voxel_bounds(const std::string& text, const std::string& where) {
  const std::vector<std::string> parts = split(text, ',');
  if (parts.size() != 6)
    throw InputError(where, "expected six numbers x0,y0,z0,x1,y1,z1, got '" + text + "'");
  double v[6];
  for (int i = 0; i < 6; ++i) {
    const std::string& p = parts[size_t(i)];
    char* end = nullptr;
    v[i] = std::strtod(p.c_str(), &end);
    if (p.empty() || end != p.c_str() + p.size() || !std::isfinite(v[i]))
      throw InputError(where, "'" + p + "' is not a finite number");
  }
  const Aabb box{dvec3(v[0], v[1], v[2]), dvec3(v[3], v[4], v[5])};
  for (int a = 0; a < 3; ++a)
    if (!(box.hi[a] > box.lo[a]))
      throw InputError(where, "the upper corner must exceed the lower one on every axis");
  return box;
}

Aabb cubic_bounds(const Aabb& box, const std::string& where) {
  if (box.empty()) throw InputError(where, "nothing to voxelize (no triangles)");
  const dvec3 e = box.extent();
  const double side = std::max({e.x, e.y, e.z});
  if (!(side > 0.0)) throw InputError(where, "the triangles span no volume; give --bounds");
  const dvec3 c = box.center();
  return {c - 0.5 * side, c + 0.5 * side};
}

bool voxelize_job_uses_gl(const VoxelizeJob& job) {
  return job.backend == "gl";
}

Backend voxelize_job_backend(const VoxelizeJob& job) {
  if (voxelize_job_uses_gl(job)) return Backend::cpu;
  return job.backend.empty() ? default_backend() : parse_backend(job.backend);
}

nlohmann::json run_voxelize_job(const VoxelizeJob& job, const nlohmann::json& meta) {
  if (!job.out.empty()) check_output_path(job.out, {".binvox"}, "binvox grid");  // before work
  if (!job.stats.empty()) check_output_path(job.stats, {".json"}, "stats JSON");
  const bool gl = voxelize_job_uses_gl(job);
  const Backend backend = voxelize_job_backend(job);
  const Registry<Voxelizer>& registry = gl ? gl_voxelizer_registry() : voxelizer_registry();
  if (gl && registry.names().empty())
    throw InputError("--backend",
                     "gl: this program has no OpenGL voxelizers (built without "
                     "DEEPVOX_GL, or EGL/OpenGL missing at build time)");
  auto method = registry.create(job.method, StrategyParams::parse(job.params));
  if (!method->supports(backend))
    throw InputError("--backend", "voxelizer '" + method->name() + "' does not run on " +
                                      to_string(backend) + " in this build");
  require_backend(backend);
  const ivec3 res = parse_voxel_resolution(job.res);
  const Aabb given = job.bounds.empty() ? Aabb{} : parse_voxel_bounds(job.bounds);

  const Scene scene = load_scene(job.input);
  const TriangleSoup soup = triangle_soup(scene);
  const Aabb bounds = job.bounds.empty() ? cubic_bounds(soup.bounds(), job.input) : given;
  const GridSpec spec = make_box_grid(res, bounds, "--bounds");

  VoxelizeResult result = method->voxelize(backend, soup, spec);
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
  if (!meta.empty()) stats["meta"] = meta;
  if (job.compare_exact) {
    const ExactVoxelization exact = voxelize_exact(soup, spec, true);
    stats["exact"] = {{"ms", exact.milliseconds},
                      {"metrics", compare_with_exact(result.grid, exact).to_json()}};
  }
  if (!job.out.empty()) {
    write_binvox(job.out, result.grid);
    const int max_dim = std::max({res.x, res.y, res.z});
    stats["binvox"] = {
        {"path", job.out}, {"translate", vec(bounds.lo)}, {"scale", spec.voxel_size().x * max_dim}};
  }
  if (!job.stats.empty()) write_json(job.stats, stats);
  return stats;
}

}  // namespace dv
