// Helpers of the viewer tests: running a shell command with its output, reading a file whole,
// and an independent computation of the viewer's error view through `deepvox probe`: each
// pixel's visible surface point found by this file's own camera rays (make_camera_view and
// camera_ray_direction, not the rasterizer's projection that engine/raster/visible_surface uses)
// and a walk over every hit, written to a CSV and asked of `deepvox probe` for the method and for
// `reference`; E = mean over lights of |T' - T| (docs/viewer.md).
#pragma once

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cuda/buffer.h"
#include "engine/raster/camera_rays.h"
#include "engine/scene/ray_query.h"
#include "engine/scene/scene_view.h"
#include "experiments/source_paths.h"

namespace dv::test {

struct ShellResult {
  int exit_code;
  std::string output;
};

inline ShellResult shell(const std::string& cmd) {
  FILE* pipe = popen((cmd + " 2>&1").c_str(), "r");
  std::string out;
  char buf[4096];
  while (size_t n = fread(buf, 1, sizeof buf, pipe)) out.append(buf, n);
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status), out};
}

inline std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

inline const std::string kDeepvox = test::binary_dir() + "/bin/deepvox";

struct IndependentError {
  std::vector<double> error;  // per pixel; NaN where the ray meets no visible surface
  double max = 0.0, mean = 0.0;
  int64_t pixels = 0;
  std::string failure;  // non-empty when a probe run failed
};

// Rows of a `deepvox probe` output CSV: the per-light values after x, y, z.
inline std::vector<std::vector<double>> read_probe_csv(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::vector<std::vector<double>> rows;
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::stringstream fields(line);
    for (std::string f; std::getline(fields, f, ',');) row.push_back(std::stod(f));
    rows.push_back(std::vector<double>(row.begin() + 3, row.end()));
  }
  return rows;
}

// `camera` at its image size; `method_args`: the shadow options as `deepvox probe` takes them.
inline IndependentError independent_error(const std::string& scene_path, const Scene& scene,
                                          const Camera& camera, const std::string& method_args,
                                          const std::filesystem::path& dir) {
  const SceneData data(scene, Memory::host);
  const SceneView& s = data.view();
  const CameraView view = make_camera_view(camera);
  IndependentError result;
  result.error.assign(size_t(camera.width) * camera.height, NAN);
  std::vector<size_t> pixel_of_point;
  std::ofstream points(dir / "independent_points.csv");
  points << "x,y,z\n";
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const dvec3 direction = camera_ray_direction(view, x, y);
      const ShearedRay ray = make_sheared_ray(view.position, direction);
      double nearest = INFINITY;
      for_each_hit(s, ray, 0.0, INFINITY, [&](const RayHit& h) {
        if (s.objects[s.triangle_object[h.triangle]].alpha > 0.0 && h.t < nearest) nearest = h.t;
        return true;
      });
      if (!std::isfinite(nearest)) continue;
      const dvec3 p = view.position + direction * nearest;
      char line[128];
      std::snprintf(line, sizeof line, "%.17g,%.17g,%.17g\n", p.x, p.y, p.z);
      points << line;
      pixel_of_point.push_back(size_t(y) * camera.width + x);
    }
  points.close();
  const std::string probe = kDeepvox + " probe " + scene_path + " --backend cpu --points " +
                            (dir / "independent_points.csv").string();
  const ShellResult approx =
      shell(probe + " " + method_args + " --out " + (dir / "independent_method.csv").string());
  const ShellResult exact =
      shell(probe + " --shadows reference --out " + (dir / "independent_oracle.csv").string());
  if (approx.exit_code != 0 || exact.exit_code != 0) {
    result.failure = approx.output + exact.output;
    return result;
  }
  const auto a = read_probe_csv(dir / "independent_method.csv");
  const auto t = read_probe_csv(dir / "independent_oracle.csv");
  double sum = 0.0;
  for (size_t i = 0; i < pixel_of_point.size(); ++i) {
    double total = 0.0;
    for (size_t l = 0; l < t[i].size(); ++l) total += std::abs(a[i][l] - t[i][l]);
    const double e = total / double(t[i].size());
    result.error[pixel_of_point[i]] = e;
    result.max = std::max(result.max, e);
    sum += e;
  }
  result.pixels = int64_t(pixel_of_point.size());
  result.mean = result.pixels ? sum / double(result.pixels) : 0.0;
  return result;
}

}  // namespace dv::test
