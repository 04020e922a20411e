// Accuracy of deep-shadow-map visibility against the exact oracle, with its cost: for each scene
// and configuration (volume sampling midpoint or Hadwiger's pre-compressed table, volume step
// scale, eps), the maps are generated, and the transmittance at points on texel-centre rays
// (so the error is that of the visibility function, not of texel placement; bias 0) is compared
// with the oracle. Reports nodes, bytes, generation time and mean / 99th-percentile / max error;
// pairs of rows at equal node count compare the table with plain sampling (Hadwiger 2006 §3.2).
// (Error summary: experiments/harness/error_summary.h, as the suite harness reports it.)
// Run: build/bin/dsm_accuracy [--backend cpu|cuda] [--points N] [--res R] > results.json
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/device_memory.h"
#include "experiments/harness/error_summary.h"
#include "io/scene_loader.h"
#include "strategies/shadow/light_faces.h"
#include "strategies/shadow/probe.h"
#include "tests/support/paths.h"

namespace dv {
namespace {

struct Config {
  std::string volume;
  double step_scale;
  float eps;
  int table_bins = 64;
};

// Points along texel-centre rays of every face, inside the scene bounds and the light's cone.
std::vector<dvec3> texel_ray_points(const SceneData& data, int res, int count, unsigned seed) {
  const SceneView& s = data.view();
  const std::vector<LightView>& lights = data.host_lights();
  const LightMapLayout layout = light_map_layout(lights, s.bounds, s.diagonal, res);
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> texel(0, res - 1);
  std::uniform_int_distribution<size_t> face(0, layout.faces.size() - 1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<dvec3> points;
  for (int tries = 0; int(points.size()) < count && tries < 100 * count; ++tries) {
    const size_t f = face(rng);
    const PixelRay ray = pixel_ray(layout.faces[f].projection, texel(rng), texel(rng));
    const dvec3 p = ray.origin + ray.direction * (u(rng) * 1.5 * s.diagonal);
    if (!s.bounds.contains(p)) continue;
    int light = 0;
    while (layout.lights[size_t(light)].first_face + layout.lights[size_t(light)].face_count <=
           int(f))
      ++light;
    if (outside_light_cone(lights[size_t(light)], p)) continue;
    if (face_of(layout.lights[size_t(light)], lights[size_t(light)], p) != int(f)) continue;
    points.push_back(p);
  }
  return points;
}

nlohmann::json run(const std::string& scene_name, const Config& c, Backend backend, int res,
                   const std::vector<dvec3>& points, const std::vector<double>& exact,
                   const SceneData& data) {
  char eps[32];
  std::snprintf(eps, sizeof eps, "eps=%.9g", c.eps);
  auto method = shadow_registry().create(
      "dsm",
      StrategyParams::parse({"res=" + std::to_string(res), eps, "bias=0", "slope=0",
                             "volume=" + c.volume, "step_scale=" + std::to_string(c.step_scale),
                             "table_bins=" + std::to_string(c.table_bins)}));
  const ProbeResults r = probe_transmittance(backend, data, *method, points);
  std::vector<double> errors;
  for (size_t i = 0; i < exact.size(); ++i)  // every (point, light) answer
    errors.push_back(std::abs(r.transmittance[i] - exact[i]));
  const ErrorSummary e = summarize_errors(std::move(errors));
  const nlohmann::json stats = method->stats();
  return {{"scene", scene_name},
          {"volume", c.volume},
          {"step_scale", c.step_scale},
          {"eps", c.eps},
          {"table_bins", c.volume == "table" ? nlohmann::json(c.table_bins) : nlohmann::json()},
          {"res", res},
          {"nodes", stats["storage"]["nodes"]},
          {"bytes_in_nodes", stats["storage"]["bytes_in_nodes"]},
          {"generation_ms", stats["generation_ms"]},
          {"points", points.size()},
          {"mean_error", e.mean},
          {"p99_error", e.p99},
          {"max_error", e.max}};
}

}  // namespace
}  // namespace dv

int main(int argc, char** argv) {
  using namespace dv;
  Backend backend = default_backend();
  int count = 20000, res = 256;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i];
    if (key == "--backend") backend = parse_backend(argv[i + 1]);
    if (key == "--points") count = std::stoi(argv[i + 1]);
    if (key == "--res") res = std::stoi(argv[i + 1]);
  }
  std::vector<Config> configs;
  for (double scale : {4.0, 2.0, 1.0, 0.5, 0.25}) configs.push_back({"midpoint", scale, 0.0f});
  for (int bins : {64, 256})
    for (double scale : {4.0, 2.0, 1.0}) configs.push_back({"table", scale, 0.0f, bins});
  configs.push_back({"midpoint", 1.0, 0.02f});
  configs.push_back({"table", 2.0, 0.02f, 256});
  nlohmann::json rows = nlohmann::json::array();
  for (const char* name : {"ct-phantom.json", "demo.json"}) {
    const Scene scene = load_scene(test::source_dir() + "/scenes/" + name);
    const SceneData data(scene, memory_of(backend));
    const std::vector<dvec3> points = texel_ray_points(data, res, count, 7);
    auto oracle = shadow_registry().create("reference");
    const std::vector<double> exact =
        probe_transmittance(backend, data, *oracle, points).transmittance;
    for (const Config& c : configs) {
      rows.push_back(run(name, c, backend, res, points, exact, data));
      std::cerr << rows.back().dump() << "\n";
    }
  }
  nlohmann::json out = {{"device", backend == Backend::cuda ? cuda_device_name() : "cpu"},
                        {"backend", to_string(backend)},
                        {"rows", rows}};
  std::cout << out.dump(1) << "\n";
  return 0;
}
