// Buchacher 2014 Tables 1 and 2 reproduced (voxelization time per method and model, filled
// voxels), plus cubic grids: the thesis models (simple quad, 2 triangles; complex quad, 11,858;
// axis-aligned cube, 12; the shared bunny scan midpoint-subdivided to 58,784; a Buddha-scale
// bunny subdivided to 940,544) at W x W x 32 for W in --sizes and at N^3 for N in --cubic, with
// every registered voxelizer that runs on the backend. Per row: the mean time per pass over
// --runs runs (after a warm-up on CUDA; "clear" is the method's own fresh grid, and per grid
// "clear_ms" times VoxelGrid::clear alone, the thesis's "Leeren des Voxelgitters"), the time
// without clear, upload, host packing and atlas update (what the thesis's Table 1 counts; it
// lists the atlas update apart, as passes_ms does), the filled voxels, the metrics against `exact`
// where the grid has at most --exact-max-voxels voxels. `exact` is a row only on the CPU.
// "tables" repeats time and filled voxels in the thesis's layout (model -> method -> sizes).
//
// Placement: every grid is the model's bounding cube grown by 10 %, so no face lies on the
// grid's boundary; the quads face the depth axis (the view of the point methods) at a depth
// that is no slice plane for any power-of-two depth up to 1024. The thesis instead squashed
// the model into a shortened frustum, which maps onto the same voxels.
// Run: build/bin/voxel_tables [--backend cpu|cuda] [--sizes 32,64,128,256,512]
//        [--cubic 64,128,256,512,1024] [--models quad,complex-quad,cube,bunny,buddha]
//        [--methods all] [--runs N] [--atlas 512,2048] [--exact-max-voxels V] > tables.json
// CPU smoke test: voxel_tables --backend cpu --sizes 32,64 --cubic 64 --models quad,cube,bunny
#include <algorithm>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/device_memory.h"
#include "core/pass_timer.h"
#include "generators/mesh_generators.h"
#include "strategies/voxelizer/exact_voxelizer.h"
#include "strategies/voxelizer/voxel_metrics.h"
#include "strategies/voxelizer/voxelizer.h"
#include "tests/support/paths.h"

namespace dv {
namespace {

struct Options {
  Backend backend = default_backend();
  std::vector<int> sizes{32, 64, 128, 256, 512}, cubic{64, 128, 256, 512, 1024};
  std::vector<std::string> models{"quad", "complex-quad", "cube", "bunny", "buddha"};
  std::vector<std::string> methods;  // empty: every registered one that runs on the backend
  std::vector<int> atlas{512, 2048};
  int runs = 0;  // 0: 10 on CUDA, 1 on the CPU
  int64_t exact_max_voxels = int64_t(512) * 512 * 512;
};

struct Model {
  TriangleSoup soup;
  Aabb bounds;
};

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) out.push_back(item);
  return out;
}

std::vector<int> split_ints(const std::string& text) {
  std::vector<int> out;
  for (const std::string& item : split(text)) out.push_back(std::stoi(item));
  return out;
}

Aabb grown_cube(const Aabb& box) {
  const double half = 0.55 * std::max({box.extent().x, box.extent().y, box.extent().z});
  return {box.center() - dvec3(half), box.center() + dvec3(half)};
}

Model make_model(const std::string& name) {
  const std::string assets = test::source_dir() + "/assets";
  if (name == "quad" || name == "complex-quad") {
    // The generator's quad lies in the x-z plane: turn it to face +z and lift it to z = 0.1.
    const TriangleMesh mesh = name == "quad" ? make_quad(1.0) : make_subdivided_quad(1.0, 11858);
    const dmat4 face_z(dvec4(1, 0, 0, 0), dvec4(0, 0, 1, 0), dvec4(0, 1, 0, 0),
                       dvec4(0, 0, 0.1, 1));
    return {triangle_soup(mesh, face_z), grown_cube({dvec3(-0.5), dvec3(0.5)})};
  }
  Model m;
  if (name == "cube")
    m.soup = triangle_soup(make_box(dvec3(-0.5), dvec3(0.5)));
  else if (name == "bunny" || name == "buddha")
    m.soup = triangle_soup(make_bunny(assets, name == "bunny" ? 2 : 4));
  else
    throw InputError("--models", "unknown model '" + name + "'");
  Aabb box;
  for (const dvec3& p : m.soup.corners) box.extend(p);
  m.bounds = grown_cube(box);
  return m;
}

// The voxelizer with the first atlas side that packs the model (atlas methods), else plain.
VoxelizeResult run_once(const std::string& method, const Options& o, const TriangleSoup& soup,
                        const GridSpec& spec, std::unique_ptr<Voxelizer>& voxelizer) {
  if (voxelizer) return voxelizer->voxelize(o.backend, soup, spec);
  const bool atlas = voxelizer_registry().create(method)->params().contains("atlas");
  for (size_t i = 0; i < (atlas ? o.atlas.size() : 1); ++i) {
    auto made = voxelizer_registry().create(
        method,
        atlas ? StrategyParams::parse({"atlas=" + std::to_string(o.atlas[i])}) : StrategyParams());
    try {
      VoxelizeResult r = made->voxelize(o.backend, soup, spec);
      voxelizer = std::move(made);
      return r;
    } catch (const InputError&) {
      if (!atlas || i + 1 == o.atlas.size()) throw;
    }
  }
  throw Error("unreachable");
}

nlohmann::json run_method(const std::string& method, const Options& o, const Model& m,
                          const GridSpec& spec, const ExactVoxelization* exact) {
  nlohmann::json row = {{"method", method}};
  try {
    std::unique_ptr<Voxelizer> voxelizer;
    VoxelizeResult r = run_once(method, o, m.soup, spec, voxelizer);
    const bool warm_up = o.backend == Backend::cuda;
    std::map<std::string, double> sums;
    for (int run = 0; run < o.runs; ++run) {
      if (run > 0 || warm_up) r = run_once(method, o, m.soup, spec, voxelizer);
      for (const VoxelizePass& p : r.passes) sums[p.name] += p.milliseconds / o.runs;
    }
    double work = 0.0;
    for (const auto& [name, ms] : sums)
      if (name != "clear" && name != "upload" && name != "pack" && name != "atlas_update")
        work += ms;
    row["passes_ms"] = sums;
    row["ms"] = work;
    row["filled"] = r.grid.popcount();
    row["counters"] = r.counters;
    row["params"] = voxelizer->params();
    if (exact) row["metrics"] = compare_with_exact(r.grid, *exact).to_json();
  } catch (const std::exception& e) {
    row["error"] = e.what();
  }
  return row;
}

double clear_ms(const GridSpec& spec, Backend backend) {
  VoxelGrid grid(spec, memory_of(backend));
  grid.clear();  // warm-up
  PassTimer timer(backend);
  grid.clear();
  return timer.stop();
}

void sweep(const Options& o, const std::string& table, const std::string& name, const Model& m,
           const std::vector<ivec3>& grids, nlohmann::json& rows, nlohmann::json& tables) {
  for (const ivec3& res : grids) {
    const GridSpec spec = make_box_grid(res, m.bounds, "voxel_tables");
    const bool affordable = spec.voxel_count() <= o.exact_max_voxels;
    const ExactVoxelization exact =
        affordable ? voxelize_exact(m.soup, spec, true) : ExactVoxelization{};
    nlohmann::json grid = {
        {"table", table},
        {"model", name},
        {"res", {res.x, res.y, res.z}},
        {"clear_ms", clear_ms(spec, o.backend)},
        {"exact_filled", affordable ? nlohmann::json(exact.exact.popcount()) : nlohmann::json()},
        {"exact_ms", affordable ? nlohmann::json(exact.milliseconds) : nlohmann::json()},
        {"methods", nlohmann::json::array()}};
    for (const std::string& method : o.methods) {
      const bool is_exact = method == "exact";
      if (!voxelizer_registry().create(method)->supports(o.backend) || (is_exact && !affordable))
        continue;
      nlohmann::json row = run_method(method, o, m, spec, affordable ? &exact : nullptr);
      if (table == "xy" && !row.contains("error")) {
        tables["time_ms"][name][method].push_back(row["ms"]);
        tables["filled"][name][method].push_back(row["filled"]);
      }
      std::cerr << name << " " << res.x << "x" << res.y << "x" << res.z << " " << row.dump()
                << "\n";
      grid["methods"].push_back(std::move(row));
    }
    rows.push_back(std::move(grid));
  }
}

}  // namespace
}  // namespace dv

int main(int argc, char** argv) {
  using namespace dv;
  try {
    Options o;
    if (argc % 2 == 0) throw InputError(argv[argc - 1], "option without a value");
    for (int i = 1; i + 1 < argc; i += 2) {
      const std::string key = argv[i], value = argv[i + 1];
      if (key == "--backend")
        o.backend = parse_backend(value);
      else if (key == "--sizes")
        o.sizes = split_ints(value);
      else if (key == "--cubic")
        o.cubic = split_ints(value);
      else if (key == "--models")
        o.models = split(value);
      else if (key == "--methods" && value != "all")
        o.methods = split(value);
      else if (key == "--runs")
        o.runs = std::stoi(value);
      else if (key == "--atlas")
        o.atlas = split_ints(value);
      else if (key == "--exact-max-voxels")
        o.exact_max_voxels = std::stoll(value);
      else if (key != "--methods")
        throw InputError(key, "unknown option");
    }
    if (o.runs <= 0) o.runs = o.backend == Backend::cuda ? 10 : 1;
    if (o.methods.empty()) o.methods = voxelizer_registry().names();
    require_backend(o.backend);
    nlohmann::json rows = nlohmann::json::array(), tables = nlohmann::json::object(),
                   models = nlohmann::json::array();
    for (const std::string& name : o.models) {
      const Model m = make_model(name);
      models.push_back({{"model", name}, {"triangles", m.soup.triangle_count()}});
      std::vector<ivec3> xy, cubic;
      for (int s : o.sizes) xy.push_back({s, s, 32});
      for (int s : o.cubic) cubic.push_back({s, s, s});
      sweep(o, "xy", name, m, xy, rows, tables);
      sweep(o, "cubic", name, m, cubic, rows, tables);
    }
    const nlohmann::json out = {{"device", o.backend == Backend::cuda ? cuda_device_name() : "cpu"},
                                {"backend", to_string(o.backend)},
                                {"runs", o.runs},
                                {"sizes", o.sizes},
                                {"cubic", o.cubic},
                                {"atlas_sides_tried", o.atlas},
                                {"exact_max_voxels", o.exact_max_voxels},
                                {"models", models},
                                {"tables", tables},
                                {"grids", rows}};
    std::cout << out.dump(1) << "\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "voxel_tables: " << e.what() << "\n";
    return 1;
  }
}
