// The calibrated error model (error_model.h).
#include "experiments/advise/error_model.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <set>
#include <sstream>

#include "core/error.h"
#include "core/json_reader.h"
#include "core/number_text.h"
#include "experiments/harness/aa_controls.h"
#include "experiments/harness/recorded_runs.h"
#include "experiments/harness/rows.h"
#include "experiments/harness/suite_file.h"
#include "experiments/harness/timing.h"
#include "render/load/scene_loader.h"
#include "strategies/shadow/effect_planner.h"

namespace dv {

namespace fs = std::filesystem;

const char* to_string(LightKind k) {
  switch (k) {
    case LightKind::none:
      return "none";
    case LightKind::opaque:
      return "opaque";
    case LightKind::translucent:
      return "translucent";
    case LightKind::media:
      return "media";
  }
  return "none";
}

namespace {

LightKind kind_named(const std::string& name, const std::string& where) {
  for (LightKind k : {LightKind::none, LightKind::opaque, LightKind::translucent, LightKind::media})
    if (name == to_string(k)) return k;
  throw InputError(where, "unknown light kind '" + name + "'");
}

// The angle a box's bounding sphere subtends from the light, over the light's field.
double caster_fraction(const LightView& l, const Aabb& box, double scene_diagonal) {
  const double radius = 0.5 * glm::length(box.extent());
  if (l.type == LightType::directional) return std::min(1.0, 2.0 * radius / scene_diagonal);
  const double d = glm::length(box.center() - l.position);
  const double angle = d <= radius ? std::numbers::pi : 2.0 * std::asin(radius / d);
  const double field = l.type == LightType::spot
                           ? 2.0 * std::acos(std::clamp(l.cos_cutoff, -1.0, 1.0))
                           : 0.5 * std::numbers::pi;  // an omni light's cube face
  return std::min(1.0, angle / std::max(field, 1e-9));
}

}  // namespace

nlohmann::json LightStats::to_json() const {
  return {{"kind", to_string(kind)},           {"casters", casters}, {"opaque", opaque},
          {"translucent", translucent},        {"media", media},     {"volumes", volumes},
          {"smallest_caster", smallest_caster}};
}

LightStats LightStats::from_json(const nlohmann::json& j) {
  JsonReader r(j, "error model", "/lights");
  LightStats s;
  s.kind = kind_named(r.string("kind"), "error model");
  s.casters = r.integer("casters");
  s.opaque = r.integer("opaque");
  s.translucent = r.integer("translucent");
  s.media = r.integer("media");
  s.volumes = r.integer("volumes");
  s.smallest_caster = r.number("smallest_caster");
  r.finish();
  return s;
}

std::vector<LightStats> light_stats(const SceneData& scene) {
  std::vector<LightStats> out;
  const std::vector<Aabb>& boxes = scene.host_object_bounds();
  const double diagonal = std::max(scene.view().diagonal, 1e-12);
  for (int l = 0; l < int(scene.host_lights().size()); ++l) {
    const LightReach r = light_reach(scene, l);
    LightStats s;
    s.casters = int(r.casters.size());
    s.opaque = r.opaque;
    s.translucent = r.translucent;
    s.media = r.media;
    s.volumes = r.volumes;
    s.kind = s.media + s.volumes > 0 ? LightKind::media
             : s.translucent > 0     ? LightKind::translucent
             : s.opaque > 0          ? LightKind::opaque
                                     : LightKind::none;
    for (int i : r.casters) {
      const double f = caster_fraction(scene.host_lights()[size_t(l)], boxes[size_t(i)], diagonal);
      s.smallest_caster = s.smallest_caster == 0.0 ? f : std::min(s.smallest_caster, f);
    }
    out.push_back(s);
  }
  return out;
}

nlohmann::json ErrorModel::to_json() const {
  nlohmann::json j = {{"format", kErrorModelFormat},
                      {"version", version},
                      {"source", source},
                      {"margin", margin},
                      {"metric", metric},
                      {"scenes", nlohmann::json::array()}};
  for (const CalibrationScene& s : scenes) {
    nlohmann::json scene = {{"scene", s.scene},
                            {"lights", nlohmann::json::array()},
                            {"configs", nlohmann::json::array()}};
    for (const LightStats& l : s.lights) scene["lights"].push_back(l.to_json());
    for (const CalibratedConfig& c : s.configs)
      scene["configs"].push_back({{"shadows", c.shadows.to_json()["shadows"]},
                                  {"p95", c.p95},
                                  {"frame_ms", c.frame_ms},
                                  {"bytes", c.bytes}});
    j["scenes"].push_back(scene);
  }
  return j;
}

ErrorModel read_error_model(const std::string& path) {
  const nlohmann::json j = parse_json_file(path);
  if (!j.is_object() || j.value("format", std::string()) != kErrorModelFormat)
    throw InputError(
        path, std::string("not an error model (\"format\" must be \"") + kErrorModelFormat + "\")");
  JsonReader r(j, path, "");
  r.string("format");
  ErrorModel m;
  m.version = r.integer("version");
  if (m.version < 1 || m.version > kErrorModelVersion)
    throw InputError(path, "error model version " + std::to_string(m.version) +
                               " is not one this build reads (1.." +
                               std::to_string(kErrorModelVersion) +
                               "): regenerate it with `deepvox advise --calibrate RUN_DIR`");
  m.source = r.raw("source");
  m.margin = r.number("margin");
  m.metric = r.string("metric");
  if (m.metric != kStrataMetric && m.metric != kVisibleMetric)
    r.fail("metric", std::string("this build predicts ") + kStrataMetric + " or " + kVisibleMetric);
  for (JsonReader& s : r.children("scenes")) {
    CalibrationScene scene;
    scene.scene = s.string("scene");
    for (const nlohmann::json& l : s.raw("lights"))
      scene.lights.push_back(LightStats::from_json(l));
    for (JsonReader& c : s.children("configs")) {
      CalibratedConfig config;
      config.shadows = shadow_config_from_json(
          {{"format", kShadowConfigFormat}, {"version", 1}, {"shadows", c.raw("shadows")}}, path);
      config.p95 = c.number("p95");
      config.frame_ms = c.number("frame_ms");
      config.bytes = c.number("bytes");
      c.finish();
      scene.configs.push_back(std::move(config));
    }
    s.finish();
    m.scenes.push_back(std::move(scene));
  }
  r.finish();
  return m;
}

void write_error_model(const std::string& path, const ErrorModel& model) {
  std::ofstream out(path);
  if (!out) throw InputError(path, "cannot write the error model");
  out << model.to_json().dump(1) << "\n";
  if (!out) throw InputError(path, "cannot write the error model");
}

std::string default_error_model_path() {
  for (const std::string& root : data_roots()) {
    const fs::path p = fs::path(root) / "experiments" / "calibration" / "error-model.json";
    if (fs::is_regular_file(p)) return p.string();
  }
  throw InputError("error model",
                   "experiments/calibration/error-model.json not found with this build");
}

namespace {

// "k=v k=v" (rows.csv's params column) as a map.
std::map<std::string, std::string> params_of(const std::string& text) {
  std::map<std::string, std::string> out;
  std::istringstream in(text);
  std::string item;
  while (in >> item)
    if (const size_t eq = item.find('='); eq != std::string::npos)
      out[item.substr(0, eq)] = item.substr(eq + 1);
  return out;
}

}  // namespace

ErrorModel calibrate_error_model(const std::string& run_dir) {
  const std::string rows_path = (fs::path(run_dir) / "rows.csv").string();
  ErrorModel model;
  model.source = {{"run", fs::path(run_dir).filename().string()}};
  nlohmann::json meta;
  if (const fs::path file = fs::path(run_dir) / "meta.json"; fs::is_regular_file(file)) {
    meta = parse_json_file(file.string());
    if (meta.contains("run")) {
      const nlohmann::json& run = meta["run"];
      for (const char* key : {"git_sha", "backend", "device", "command_line"})
        if (run.contains(key)) model.source[key] = run[key];
    }
  }
  // The folder and the further runs its runs.json names (a replicate protocol's rounds): errors
  // and bytes from the folder's rows, each configuration's frame time the median over the runs.
  std::vector<fs::path> runs = {fs::path(run_dir)};
  if (meta.is_object())
    for (const fs::path& other :
         recorded_runs(run_dir, meta.value("suite", ""), meta.value("suite_hash", "")))
      runs.push_back(other);
  model.source["runs"] = runs.size();
  // Per scene, per configuration (its params): the figures the model keeps. A/A copies (the
  // same configuration measured twice in a run) are left out.
  std::map<std::string, std::map<std::string, CalibratedConfig>> items;
  std::map<std::string, std::map<std::string, std::vector<double>>> frame_ms;
  std::map<std::string, std::map<std::string, int>> have;  // bit 1: p95, 2: bytes
  for (size_t r = 0; r < runs.size(); ++r) {
    const std::vector<Row> rows = read_rows_csv((runs[r] / "rows.csv").string());
    if (r == 0)
      model.metric =
          std::any_of(rows.begin(), rows.end(),
                      [](const Row& row) { return row.metric + ":" + row.stat == kStrataMetric; })
              ? kStrataMetric
              : kVisibleMetric;
    for (const Row& row : rows) {
      if (row.kind != "shadow" || row.strategy != "dsm" || is_aa_copy(row.params)) continue;
      if (row.metric == "frame_ms" && row.stat == "value")
        frame_ms[row.scene][row.params].push_back(row.value);
      if (r > 0) continue;
      CalibratedConfig& c = items[row.scene][row.params];
      c.shadows.name = "auto";
      c.shadows.params = params_of(row.params);
      if (row.metric + ":" + row.stat == model.metric) {
        c.p95 = row.value;
        have[row.scene][row.params] |= 1;
      } else if (row.metric == "bytes" && row.stat == "value") {
        c.bytes = row.value;
        have[row.scene][row.params] |= 2;
      }
    }
  }
  if (items.empty())
    throw InputError(rows_path, "no dsm rows of kind shadow: not an accuracy suite run");
  for (auto& [scene_path, configs] : items) {
    CalibrationScene s;
    s.scene = scene_path;
    const std::string resolved = resolve_data_file(scene_path, rows_path);
    const Scene scene = load_scene(resolved);
    s.lights = light_stats(SceneData(scene, Memory::host));
    for (auto& [params, config] : configs) {
      std::vector<double>& times = frame_ms[scene_path][params];
      if (have[scene_path][params] != 3 || times.empty()) continue;
      config.frame_ms = spread_of(times).median;
      s.configs.push_back(std::move(config));
    }
    model.scenes.push_back(std::move(s));
  }
  return model;
}

BudgetPrediction predict_budget(const ErrorModel& model, const std::vector<LightStats>& lights,
                                double budget) {
  BudgetPrediction out;
  // Per light, the calibration scenes that answer for it.
  std::vector<std::vector<const CalibrationScene*>> matched(lights.size());
  out.lights.resize(lights.size());
  bool every_light = true;
  for (size_t l = 0; l < lights.size(); ++l) {
    LightPrediction& p = out.lights[l];
    const LightStats& s = lights[l];
    if (s.kind == LightKind::none) {
      p.confident = true;
      p.why = "reaches no caster: no shadows to get wrong";
      continue;
    }
    double finest = 1.0;
    for (const CalibrationScene& c : model.scenes)
      for (const LightStats& cl : c.lights)
        if (cl.kind == s.kind) {
          matched[l].push_back(&c);
          finest = std::min(finest, cl.smallest_caster);
          break;
        }
    if (matched[l].empty()) {
      p.why =
          std::string("no calibration scene has a light with ") + to_string(s.kind) + " casters";
      every_light = false;
    } else if (s.smallest_caster < 0.5 * finest) {
      p.why = "its smallest caster spans " + significant_text(s.smallest_caster, 3) +
              " of its field, finer than half the finest the model calibrated (" +
              significant_text(finest, 3) + ")";
      every_light = false;
    } else {
      p.confident = true;
      p.why = std::to_string(matched[l].size()) + " calibration scene(s) with " +
              to_string(s.kind) + " casters answer";
    }
  }
  if (!every_light) {
    out.why = "the model cannot predict every light";
    return out;
  }
  // Candidates: the configurations every matched scene measured, keyed by their parameters.
  struct Candidate {
    ShadowConfig config;
    double predicted = 0.0, cost = 0.0;
    std::vector<double> per_light;
  };
  std::set<const CalibrationScene*> used;
  for (const auto& m : matched) used.insert(m.begin(), m.end());
  std::map<std::string, Candidate> candidates;
  std::map<std::string, int> seen_in;
  for (const CalibrationScene* c : used)
    for (const CalibratedConfig& cc : c->configs) {
      const std::string key = cc.shadows.param_line();
      Candidate& cand = candidates[key];
      cand.config = cc.shadows;
      cand.cost += cc.frame_ms / double(used.size());
      ++seen_in[key];
    }
  const Candidate* best = nullptr;
  for (auto& [key, cand] : candidates) {
    if (seen_in[key] != int(used.size())) continue;  // not measured on every matched scene
    cand.per_light.assign(lights.size(), 0.0);
    for (size_t l = 0; l < lights.size(); ++l)
      for (const CalibrationScene* c : matched[l])
        for (const CalibratedConfig& cc : c->configs)
          if (cc.shadows.param_line() == key)
            cand.per_light[l] = std::max(cand.per_light[l], cc.p95 * model.margin);
    cand.predicted = *std::max_element(cand.per_light.begin(), cand.per_light.end());
    if (cand.predicted <= budget && (!best || cand.cost < best->cost)) best = &cand;
  }
  if (!best) {
    out.why = "no calibrated configuration is predicted within " + significant_text(budget, 3);
    for (LightPrediction& p : out.lights) p.confident = false;
    return out;
  }
  out.confident = true;
  out.pick = best->config;
  for (size_t l = 0; l < lights.size(); ++l) out.lights[l].predicted = best->per_light[l];
  out.why = "the cheapest calibrated configuration (" + significant_text(best->cost, 3) +
            " ms mean calibrated frame) predicted within " + significant_text(budget, 3) + " (" +
            significant_text(best->predicted, 3) + " = worst calibrated p95 x margin " +
            significant_text(model.margin, 3) + ")";
  return out;
}

}  // namespace dv
