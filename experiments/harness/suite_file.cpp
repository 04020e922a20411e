// Suite files: strict loading, sweep expansion, shards and built-in suite lookup (suite_file.h).
#include "experiments/harness/suite_file.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "core/error.h"
#include "core/json_reader.h"
#include "core/text.h"
#include "experiments/harness/driver.h"
#include "experiments/harness/rows.h"
#include "strategies/shadow/shadow_config.h"
#include "strategies/shadow/strategy_catalog.h"

namespace dv {

namespace fs = std::filesystem;

namespace {

// A parameter value as StrategyParams reads it: strings as they are, numbers in JSON's
// shortest round-trip form, booleans as 1 / 0.
std::string value_text(const Json& v, const JsonReader& at, const std::string& key) {
  if (v.is_string()) return v.get<std::string>();
  if (v.is_boolean()) return v.get<bool>() ? "1" : "0";
  if (v.is_number()) return v.dump();
  at.fail(key, "expected a string, number or boolean");
}

std::vector<std::string> one_or_many(JsonReader& r, const std::string& key) {
  const Json& v = r.raw(key);
  std::vector<std::string> out;
  if (v.is_string()) out.push_back(v.get<std::string>());
  if (v.is_array())
    for (const Json& item : v) {
      if (!item.is_string()) r.fail(key, "expected strings");
      out.push_back(item.get<std::string>());
    }
  if (out.empty()) r.fail(key, "expected a string or a non-empty array of strings");
  return out;
}

std::map<std::string, std::string> value_map(JsonReader& r, const std::string& key) {
  std::map<std::string, std::string> out;
  if (!r.has(key)) return out;
  const Json& v = r.raw(key);
  if (!v.is_object()) r.fail(key, "expected an object of key: value");
  for (const auto& [k, item] : v.items()) out[k] = value_text(item, r, key + "/" + k);
  return out;
}

// Whether `table` declares `key` (a nested prefix's "prefix.KEY" included).
bool declares(const ParamTable& table, const std::string& key) {
  for (const ParamSpec& spec : table)
    if (spec.key == key || (spec.type == ParamSpec::Type::nested && is_nested_key(key, spec.key)))
      return true;
  return false;
}

// {"every": FAMILY, "name": ..., "params": {...}, "sizes": bool}: one spec per registered
// strategy of FAMILY (strategy_catalog.h), read from the registry when the suite loads. Without
// "name" the members are the strategies, each given the "params" its own table declares (a key
// that no member declares is an error); with "name" each member goes to that strategy's
// parameter named like the family (dsm's `storage`) over the item's "params". With "sizes"
// true a member that has a size knob runs once per value of it.
std::vector<StrategySpec> every_strategy(JsonReader& item) {
  const std::string family = item.string("every");
  const std::vector<std::string> families = catalog_registries();
  if (std::find(families.begin(), families.end(), family) == families.end()) {
    std::string known;
    for (const std::string& f : families) known += (known.empty() ? "" : ", ") + f;
    item.fail("every", "unknown strategy family '" + family + "' (known: " + known + ")");
  }
  const std::string name = item.string("name", "");
  const std::map<std::string, std::string> params = value_map(item, "params");
  const bool sizes = item.boolean("sizes", false);
  if (!name.empty()) {
    bool takes_member = false;
    for (const CatalogEntry& e : strategy_catalog())
      for (const ParamSpec& spec : e.name == name ? e.params : ParamTable{})
        takes_member |= spec.key == family && spec.type == ParamSpec::Type::name;
    if (!takes_member)
      item.fail("name", "'" + name + "' has no parameter '" + family + "' naming a " + family);
  }
  const std::vector<CatalogEntry> members = catalog_of(family, item.where("every"));
  for (const auto& [key, value] : params) {
    bool declared = !name.empty();
    for (const CatalogEntry& m : members) declared |= declares(m.params, key);
    if (!declared) item.fail("params/" + key, "no " + family + " declares '" + key + "'");
  }
  std::vector<StrategySpec> out;
  for (const CatalogEntry& m : members) {
    StrategySpec spec{name.empty() ? m.name : name, {}, {}};
    for (const auto& [key, value] : params)
      if (!name.empty() || declares(m.params, key)) spec.params[key] = value;
    if (!name.empty()) spec.params[family] = m.name;
    const std::string size_key = (name.empty() ? "" : family + ".") + m.traits.size_key;
    if (!sizes || m.traits.size_key.empty()) {
      out.push_back(spec);
      continue;
    }
    for (const std::string& size : m.traits.sizes) {
      spec.params[size_key] = size;
      out.push_back(spec);
    }
  }
  return out;
}

// Whether `earlier` already runs the member `spec` of an every item on the same scenes: the same
// strategy and, where the item names one (`family_key`), the same member.
bool runs_member(const StrategySpec& earlier, const StrategySpec& spec,
                 const std::string& family_key) {
  if (earlier.name != spec.name || earlier.scenes != spec.scenes) return false;
  if (family_key.empty()) return true;
  const auto it = earlier.params.find(family_key);
  return it != earlier.params.end() &&
         lowercase(it->second) == lowercase(spec.params.at(family_key));
}

// "name", or an array of "name" and {"name": ..., "params": {...}, "scenes": [...]} items; an
// item may name a shadow config file instead ({"config": "pick.json", "scenes": [...]}) or
// every strategy of a family ({"every": "storage", ...}, every_strategy) but those an earlier
// item already runs: a member that needs parameters of its own is named before the item.
std::vector<StrategySpec> strategy_list(JsonReader& r) {
  const Json& v = r.raw("strategy");
  std::vector<StrategySpec> out;
  if (v.is_string()) out.push_back({v.get<std::string>(), {}, {}});
  for (size_t i = 0; v.is_array() && i < v.size(); ++i) {
    if (v[i].is_string()) {
      out.push_back({v[i].get<std::string>(), {}, {}});
      continue;
    }
    if (!v[i].is_object())
      r.fail("strategy",
             "expected names or {\"name\", \"params\", \"scenes\"} or {\"every\", ...} "
             "objects");
    JsonReader item(v[i], r.file(), r.path() + "/strategy/" + std::to_string(i));
    if (item.has("every")) {
      const std::string family_key = item.has("name") ? item.string("every") : "";
      std::vector<StrategySpec> specs = every_strategy(item);
      if (item.has("scenes")) {
        const std::vector<std::string> scenes = one_or_many(item, "scenes");
        for (StrategySpec& spec : specs) spec.scenes = scenes;
      }
      item.finish();
      const size_t before = out.size();
      for (StrategySpec& spec : specs)
        if (std::none_of(out.begin(), out.begin() + long(before),
                         [&](const StrategySpec& s) { return runs_member(s, spec, family_key); }))
          out.push_back(std::move(spec));
      continue;
    }
    StrategySpec spec;
    if (item.has("config")) {  // a shadow config file (what `deepvox advise` writes)
      if (item.has("name") || item.has("params"))
        item.fail("config", "names the method and its parameters; leave name and params out");
      const ShadowConfig config =
          read_shadow_config(resolve_data_file(item.string("config"), r.file()));
      spec = {config.name, config.params, {}};
    } else {
      spec = {item.string("name"), value_map(item, "params"), {}};
    }
    if (item.has("scenes")) spec.scenes = one_or_many(item, "scenes");
    item.finish();
    out.push_back(std::move(spec));
  }
  if (out.empty()) r.fail("strategy", "expected a name or a non-empty array of strategies");
  return out;
}

// [selector, column] with both strings (a finding's side, findings.h).
void check_finding_side(JsonReader& r, const Json& side, const std::string& key) {
  if (!side.is_array() || side.size() != 2 || !side[0].is_string() || !side[1].is_string())
    r.fail(key, "expected [\"selector\", \"metric:stat\"]");
}

// The metrics of the columns a claim compares (its two sides, or a trend's column).
std::vector<std::string> compared_metrics(const Json& f) {
  std::vector<std::string> metrics;
  for (const char* side : {"lower", "than", "column"})
    if (f.contains(side)) {
      const Json& c = f[side].is_array() && f[side].size() == 2 ? f[side][1] : f[side];
      if (c.is_string()) metrics.push_back(parse_column(c.get<std::string>()).metric);
    }
  return metrics;
}

// A claim's "timer" (findings.h): present, "none" or a time metric (`X_ms`), and the metric of
// every column the claim compares, so that the timer printed is the one that decides; "none"
// only where no column is a time.
void check_timer(JsonReader& r, const Json& f, const std::string& at) {
  const std::string claim = f["claim"].get<std::string>();
  const std::vector<std::string> metrics = compared_metrics(f);
  std::string compared;
  for (const std::string& m : metrics) compared += (compared.empty() ? "" : " and ") + m;
  if (!f.contains("timer") || !f["timer"].is_string() || f["timer"].get<std::string>().empty())
    r.fail(at + "/timer", "the claim '" + claim +
                              "' names no timer: add \"timer\": the time metric that decides it "
                              "(here " +
                              compared +
                              "; e.g. generate_ms, generate.passes.count_ms, frame_ms) "
                              "or \"none\" where it compares no time");
  const std::string timer = f["timer"].get<std::string>();
  if (timer == "none") {
    for (const std::string& m : metrics)
      if (is_time_metric(m))
        r.fail(at + "/timer", "the claim '" + claim + "' compares a time (" + m +
                                  "): name it as the timer instead of \"none\"");
    return;
  }
  if (!is_time_metric(timer))
    r.fail(at + "/timer", "the claim '" + claim + "': timer '" + timer +
                              "' is not a time metric (X_ms) or \"none\"");
  for (const std::string& m : metrics)
    if (m != timer)
      r.fail(at + "/timer", "the claim '" + claim + "': its rows carry " + compared +
                                ", not the timer '" + timer + "' it names");
}

// A comparison {claim, lower, than, timer, why, why_not, lossy, not_as_paper} or a trend {claim,
// trend, over, selector, column, levels, from, timer, why, why_not, lossy, not_as_paper}
// (findings.h).
void check_findings(JsonReader& r, const Json& findings) {
  if (!findings.is_array()) r.fail("findings", "expected an array of claims");
  for (size_t i = 0; i < findings.size(); ++i) {
    const std::string at = "findings/" + std::to_string(i);
    const Json& f = findings[i];
    if (!f.is_object() || !f.contains("claim") || !f["claim"].is_string())
      r.fail(at,
             "expected {\"claim\": ..., \"lower\": [...], \"than\": [...]} or {\"claim\": "
             "..., \"trend\": ..., \"over\": ..., \"selector\": ..., \"column\": ...}");
    const bool trend = f.contains("trend");
    const std::vector<std::string> known =
        trend ? std::vector<std::string>{"claim",  "trend",   "over",  "selector",
                                         "column", "levels",  "from",  "timer",
                                         "why",    "why_not", "lossy", "not_as_paper"}
              : std::vector<std::string>{"claim", "lower",   "than",  "timer",
                                         "why",   "why_not", "lossy", "not_as_paper"};
    if (f.contains("lossy") && f["lossy"] != "expected")
      r.fail(at + "/lossy", "expected \"expected\" (the claim is about a loss, e.g. a limit)");
    for (const auto& [key, v] : f.items())
      if (std::find(known.begin(), known.end(), key) == known.end()) {
        std::string list;
        for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
        r.fail(at + "/" + key, "unknown key (known: " + list + ")");
      }
    if (f.contains("not_as_paper") &&
        (!f["not_as_paper"].is_string() || f["not_as_paper"].get<std::string>().empty()))
      r.fail(at + "/not_as_paper", "expected the reason the paper's test cannot be repeated");
    if (!trend) {
      if (!f.contains("lower") || !f.contains("than"))
        r.fail(at, "expected {\"claim\": ..., \"lower\": [...], \"than\": [...]}");
      check_finding_side(r, f["lower"], at + "/lower");
      check_finding_side(r, f["than"], at + "/than");
      check_timer(r, f, at);
      continue;
    }
    const Json& t = f["trend"];
    if (!t.is_string() || (t != "increasing" && t != "decreasing" && t != "plateau"))
      r.fail(at + "/trend", "expected \"increasing\", \"decreasing\" or \"plateau\"");
    for (const char* key : {"over", "selector", "column"})
      if (!f.contains(key) || !f[key].is_string()) r.fail(at + "/" + key, "expected a string");
    if (f.contains("levels") && (!f["levels"].is_array() || f["levels"].size() < 2))
      r.fail(at + "/levels", "expected an array of at least two levels");
    if (f.contains("from") && t != "plateau") r.fail(at + "/from", "only for a plateau");
    check_timer(r, f, at);
  }
}

// A paper map's "shape" (report.cpp's shape table): {"machine": text, "column_pairs": [[a, b],
// ...], "row_pairs": [[a, b], ...], "baseline": {"selector", "column", "paper", "source",
// "rows"}}, indices into the map's rows and value columns.
void check_shape(JsonReader& r, const Json& shape, size_t rows, size_t columns) {
  if (!shape.is_object()) r.fail("shape", "expected an object");
  const auto index_pairs = [&](const char* key, size_t limit) {
    const Json& pairs = shape.value(key, Json::array());
    if (!pairs.is_array()) r.fail(std::string("shape/") + key, "expected [[a, b], ...]");
    for (const Json& p : pairs)
      if (!p.is_array() || p.size() != 2 || !p[0].is_number_unsigned() ||
          !p[1].is_number_unsigned() || p[0].get<size_t>() >= limit || p[1].get<size_t>() >= limit)
        r.fail(std::string("shape/") + key,
               "expected pairs of indices below " + std::to_string(limit));
  };
  for (const auto& [key, v] : shape.items())
    if (key != "machine" && key != "column_pairs" && key != "row_pairs" && key != "baseline" &&
        key != "band")
      r.fail("shape/" + key,
             "unknown key (known: machine, column_pairs, row_pairs, baseline, band)");
  if (shape.contains("machine") && !shape["machine"].is_string())
    r.fail("shape/machine", "expected a sentence");
  if (shape.contains("band") && (!shape["band"].is_number() || shape["band"].get<double>() <= 0.0 ||
                                 shape["band"].get<double>() >= 1.0))
    r.fail("shape/band", "expected a relative band between 0 and 1 (0.1: within 10 %)");
  index_pairs("column_pairs", columns);
  index_pairs("row_pairs", rows);
  if (!shape.contains("baseline")) return;
  const Json& b = shape["baseline"];
  if (!b.is_object() || !b.contains("selector") || !b["selector"].is_string() ||
      !b.contains("column") || !b["column"].is_string() || !b.contains("paper") ||
      !b["paper"].is_number() || !b.contains("rows") || !b["rows"].is_array() ||
      (b.contains("source") && !b["source"].is_string()))
    r.fail("shape/baseline",
           "expected {\"selector\", \"column\", \"paper\": number, \"source\", \"rows\": [...]}");
  for (const Json& i : b["rows"])
    if (!i.is_number_unsigned() || i.get<size_t>() >= rows)
      r.fail("shape/baseline/rows", "expected row indices below " + std::to_string(rows));
}

// A paper table's mapping to our rows: {"table": FILE, "where": SELECTOR, "rows": [one
// [SELECTOR, COLUMN] or null per paper row], "columns": [one SELECTOR, [SELECTOR, COLUMN] (its
// column replaces the row's) or null per value column], "paper_as": "ms_from_fps" (optional: the
// paper's rates also shown as milliseconds)}; the counts are checked against the table when its
// file can be read here.
Json check_paper_map(JsonReader& r, const Json& map, const std::string& table_file) {
  r.string("where", "");
  const std::string paper_as = r.string("paper_as", "");
  if (!paper_as.empty() && paper_as != "ms_from_fps")
    r.fail("paper_as", "expected \"ms_from_fps\" (or nothing)");
  const Json& rows = r.raw("rows");
  const Json& columns = r.raw("columns");
  if (r.has("shape") && rows.is_array() && columns.is_array())
    check_shape(r, r.raw("shape"), rows.size(), columns.size());
  if (!rows.is_array()) r.fail("rows", "expected one [selector, column] or null per paper row");
  for (size_t i = 0; i < rows.size(); ++i)
    if (!rows[i].is_null()) check_finding_side(r, rows[i], "rows/" + std::to_string(i));
  if (!columns.is_array()) r.fail("columns", "expected one selector or null per value column");
  for (size_t i = 0; i < columns.size(); ++i)
    if (columns[i].is_array())
      check_finding_side(r, columns[i], "columns/" + std::to_string(i));
    else if (!columns[i].is_null() && !columns[i].is_string())
      r.fail("columns", "expected a selector, [selector, column] or null per value column");
  r.finish();
  if (!fs::is_regular_file(table_file)) return map;
  const Json table = parse_json_file(table_file);
  const size_t labels = size_t(table.value("label_columns", 1));
  const size_t values = table.value("columns", Json::array()).size() - labels;
  const size_t paper_rows = table.value("rows", Json::array()).size();
  if (rows.size() != paper_rows || columns.size() != values)
    r.fail("rows", "the table " + table_file + " has " + std::to_string(paper_rows) + " rows and " +
                       std::to_string(values) + " value columns; the map gives " +
                       std::to_string(rows.size()) + " and " + std::to_string(columns.size()));
  return map;
}

void check_pareto(JsonReader& r, const Json& pareto) {
  if (!pareto.is_object() || !pareto.contains("error") || !pareto.contains("cost"))
    r.fail("pareto", "expected {\"error\": [columns], \"cost\": [columns]}");
  for (const auto& [key, v] : pareto.items()) {
    if (key != "error" && key != "cost")
      r.fail("pareto/" + key, "unknown key (known: error, cost)");
    bool ok = v.is_string() || (v.is_array() && !v.empty());
    for (const Json& c : v.is_array() ? v : Json::array()) ok &= c.is_string();
    if (!ok) r.fail("pareto/" + key, "expected a column or a non-empty array of columns");
  }
}

ExperimentSpec parse_experiment(JsonReader& r, const Json& object, const std::string& file);

// The experiment's JSON with its `smoke` overrides merged: scene, strategy, sweep and columns
// replaced, params and settings merged key by key.
Json merged_smoke(JsonReader& r, const Json& object) {
  const Json& smoke = r.raw("smoke");
  if (!smoke.is_object()) r.fail("smoke", "expected an object of overrides");
  Json merged = object;
  merged.erase("smoke");
  for (const auto& [key, v] : smoke.items()) {
    if (key == "params" || key == "settings") {
      if (!v.is_object()) r.fail("smoke/" + key, "expected an object of key: value");
      if (!merged.contains(key)) merged[key] = Json::object();
      for (const auto& [k, item] : v.items()) merged[key][k] = item;
    } else if (key == "scene" || key == "strategy" || key == "sweep" || key == "columns") {
      merged[key] = v;
    } else {
      r.fail("smoke/" + key,
             "unknown override (known: scene, strategy, sweep, columns, params, settings)");
    }
  }
  // A swept key now fixed by the smoke params (or the other way round) leaves the sweep.
  if (merged.contains("sweep") && merged.contains("params"))
    for (const auto& [k, v] : merged["params"].items()) merged["sweep"].erase(k);
  if (merged.contains("sweep") && merged["sweep"].empty()) merged.erase("sweep");
  JsonReader check(merged, r.file(), r.path() + "/smoke");
  parse_experiment(check, merged, r.file());  // the smoke form must load as strictly
  return merged;
}

ExperimentSpec parse_experiment(JsonReader& r, const Json& object, const std::string& file) {
  ExperimentSpec e;
  e.name = r.string("name");
  e.kind = r.string("kind");
  const std::vector<std::string> kinds = driver_names();
  if (std::find(kinds.begin(), kinds.end(), e.kind) == kinds.end()) {
    std::string known;
    for (const std::string& n : kinds) known += (known.empty() ? "" : ", ") + n;
    r.fail("kind", "unknown experiment kind '" + e.kind + "' (known: " + known + ")");
  }
  e.description = r.string("description", "");
  e.scenes = one_or_many(r, "scene");
  for (const std::string& s : e.scenes) e.scene_paths.push_back(resolve_data_file(s, file));
  e.strategies = strategy_list(r);
  e.params = value_map(r, "params");
  e.settings = value_map(r, "settings");
  for (const auto& [key, value] : e.settings)
    if (!driver_accepts_setting(e.kind, key))
      r.fail("settings", "unknown setting '" + key + "' for kind '" + e.kind +
                             "' (known: " + driver_settings_text(e.kind) + ")");
  if (r.has("sweep")) {
    const Json& sweep = r.raw("sweep");
    if (!sweep.is_object()) r.fail("sweep", "expected an object of key: [values]");
    for (const auto& [key, values] : sweep.items()) {
      if (!values.is_array() || values.empty())
        r.fail("sweep", "'" + key + "' needs a non-empty array of values");
      if (e.params.count(key)) r.fail("sweep", "'" + key + "' is also a fixed parameter");
      std::vector<std::string> texts;
      for (const Json& v : values) texts.push_back(value_text(v, r, "sweep/" + key));
      e.sweep.emplace_back(key, texts);
    }
  }
  if (r.has("columns")) e.columns = one_or_many(r, "columns");
  if (r.has("paper")) {
    const Json& paper = r.raw("paper");
    if (paper.is_string() || paper.is_array()) {
      const Json list = paper.is_string() ? Json::array({paper}) : paper;
      if (list.empty()) r.fail("paper", "expected paper table files");
      for (size_t i = 0; i < list.size(); ++i) {
        if (list[i].is_string()) {
          e.paper_files.push_back(resolve_data_file(list[i].get<std::string>(), file));
          e.paper_maps.push_back(nullptr);
          continue;
        }
        if (!list[i].is_object())
          r.fail("paper", "expected paper table files or {\"table\", \"rows\", \"columns\"}");
        JsonReader map(list[i], r.file(), r.path() + "/paper/" + std::to_string(i));
        e.paper_files.push_back(resolve_data_file(map.string("table"), file));
        e.paper_maps.push_back(check_paper_map(map, list[i], e.paper_files.back()));
      }
    } else {
      e.paper = paper;
      if (!e.paper.is_object() || !e.paper.contains("columns") || !e.paper.contains("rows") ||
          !e.paper["columns"].is_array() || !e.paper["rows"].is_array())
        r.fail("paper",
               "expected paper table files or {\"columns\": [...], \"rows\": [[...], ...]}");
    }
  }
  if (r.has("findings")) {
    e.findings = r.raw("findings");
    check_findings(r, e.findings);
  }
  if (r.has("pareto")) {
    e.pareto = r.raw("pareto");
    check_pareto(r, e.pareto);
  }
  if (r.has("smoke")) e.smoke = merged_smoke(r, object);
  e.aa_duplicates = r.boolean("aa_duplicates", false);
  if (r.has("plots")) {
    e.plots = r.raw("plots");
    if (!e.plots.is_array()) r.fail("plots", "expected an array of plot objects");
  }
  r.finish();
  return e;
}

void check_unique_names(const Suite& s) {
  for (size_t i = 0; i < s.experiments.size(); ++i)
    for (size_t j = 0; j < i; ++j)
      if (s.experiments[i].name == s.experiments[j].name)
        throw InputError(s.file, "experiment name '" + s.experiments[i].name + "' used twice");
}

}  // namespace

std::string fnv1a_hex(const std::string& bytes) {
  uint64_t h = 1469598103934665603ull;
  for (unsigned char c : bytes) h = (h ^ c) * 1099511628211ull;
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  return hex;
}

Suite parse_suite(const std::string& text, const std::string& path) {
  const Json doc = parse_json_text(text, path);
  if (!doc.is_object()) throw InputError(path, "a suite file holds one JSON object");
  JsonReader r(doc, path, "");
  Suite s;
  s.file = path;
  s.hash = fnv1a_hex(text);
  s.name = r.string("suite");
  if (s.name.empty() || s.name.find_first_of("/\\ ") != std::string::npos)
    r.fail("suite", "the name must be non-empty without spaces or slashes (it names a folder)");
  s.description = r.string("description", "");
  s.repeat = r.integer("repeat", 3);
  if (s.repeat < 1 || s.repeat > 1000) r.fail("repeat", "expected 1..1000");
  if (r.has("practical_bands")) {
    const Json& bands = r.raw("practical_bands");
    if (!bands.is_object()) r.fail("practical_bands", "expected {\"metric[:stat]\": band, ...}");
    for (const auto& [column, band] : bands.items()) {
      if (!band.is_number() || band.get<double>() <= 0.0)
        r.fail("practical_bands/" + column, "expected a positive band in the metric's unit");
      s.practical_bands[column] = band.get<double>();
    }
  }
  std::vector<JsonReader> experiments = r.children("experiments");
  for (size_t i = 0; i < experiments.size(); ++i)
    s.experiments.push_back(parse_experiment(experiments[i], doc["experiments"][i], path));
  if (s.experiments.empty()) r.fail("experiments", "a suite needs at least one experiment");
  r.finish();
  check_unique_names(s);
  return s;
}

Suite parse_recorded_suite(const std::string& text, const std::string& path) {
  Json doc = parse_json_text(text, path);
  if (doc.is_object() && doc.contains("experiments") && doc["experiments"].is_array())
    for (Json& e : doc["experiments"]) {
      if (!e.is_object() || !e.contains("findings") || !e["findings"].is_array()) continue;
      for (Json& f : e["findings"]) {
        if (!f.is_object() || f.contains("timer")) continue;
        std::set<std::string> times, all;
        for (const std::string& m : compared_metrics(f)) {
          all.insert(m);
          if (is_time_metric(m)) times.insert(m);
        }
        if (times.empty() && !all.empty()) f["timer"] = "none";
        if (times.size() == 1 && all.size() == 1) f["timer"] = *times.begin();
      }
    }
  Suite s = parse_suite(doc.dump(), path);
  s.hash = fnv1a_hex(text);
  return s;
}

Suite load_suite(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "cannot read suite file");
  std::stringstream text;
  text << in.rdbuf();
  return parse_suite(text.str(), path);
}

Suite smoke_suite(const Suite& suite) {
  Suite out = suite;
  for (size_t i = 0; i < out.experiments.size(); ++i) {
    if (out.experiments[i].smoke.is_null()) continue;
    const Json merged = out.experiments[i].smoke;
    JsonReader r(merged, suite.file, "/experiments/" + std::to_string(i) + "/smoke");
    out.experiments[i] = parse_experiment(r, merged, suite.file);
  }
  return out;
}

std::vector<RunItem> expand_suite(const Suite& suite) {
  std::vector<RunItem> items;
  for (size_t ei = 0; ei < suite.experiments.size(); ++ei) {
    const ExperimentSpec& e = suite.experiments[ei];
    const size_t first = items.size();
    size_t points = 1;
    for (const auto& [key, values] : e.sweep) points *= values.size();
    for (size_t si = 0; si < e.scenes.size(); ++si)
      for (const StrategySpec& strategy : e.strategies) {
        if (!strategy.runs_on(e.scenes[si])) continue;
        for (size_t p = 0; p < points; ++p) {
          RunItem item;
          item.index = int(items.size());
          item.experiment = int(ei);
          item.experiment_name = e.name;
          item.kind = e.kind;
          item.scene = e.scenes[si];
          item.scene_path = e.scene_paths[si];
          item.strategy = strategy.name;
          item.params = e.params;
          for (const auto& [key, value] : strategy.params) item.params[key] = value;
          item.settings = e.settings;
          size_t rest = p;  // mixed-radix digits, the last sweep key fastest
          for (size_t k = e.sweep.size(); k-- > 0;) {
            const auto& [key, values] = e.sweep[k];
            item.params[key] = values[rest % values.size()];
            rest /= values.size();
          }
          items.push_back(std::move(item));
        }
      }
    if (!e.aa_duplicates) continue;
    const size_t end = items.size();
    for (size_t i = first; i < end; ++i) {
      RunItem copy = items[i];
      copy.index = int(items.size());
      copy.aa_copy = true;
      items.push_back(std::move(copy));
    }
  }
  return items;
}

Shard parse_shard(const std::string& text, const std::string& where) {
  Shard s;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%d/%d%c", &s.index, &s.count, &tail) != 2 || s.count < 1 ||
      s.index < 1 || s.index > s.count)
    throw InputError(where, "expected I/N with 1 <= I <= N, got '" + text + "'");
  return s;
}

std::vector<RunItem> filter_items(const std::vector<RunItem>& items, const std::string& pattern) {
  if (pattern.empty()) return items;
  std::vector<RunItem> out;
  for (const RunItem& item : items)
    for (const std::string* field : {&item.experiment_name, &item.kind, &item.strategy})
      if (field->find(pattern) != std::string::npos) {
        out.push_back(item);
        break;
      }
  return out;
}

std::string resolve_data_file(const std::string& path, const std::string& anchor_file) {
  const fs::path p(path);
  if (p.is_absolute()) return path;
  std::vector<fs::path> candidates{fs::path(anchor_file).parent_path() / p, p};
  for (const std::string& root : data_roots()) candidates.push_back(fs::path(root) / p);
  for (const fs::path& c : candidates)
    if (fs::exists(c)) return c.string();
  return path;
}

std::vector<std::string> data_roots() {
  std::vector<std::string> roots;
  if (const char* env = std::getenv("DEEPVOX_SOURCE_DIR"); env && *env) roots.push_back(env);
#ifdef DEEPVOX_SOURCE_DIR
  roots.push_back(DEEPVOX_SOURCE_DIR);
#endif
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) roots.push_back((exe.parent_path().parent_path() / "share" / "deepvox").string());
  return roots;
}

std::vector<std::string> builtin_suite_names() {
  std::vector<std::string> names;
  for (const std::string& root : data_roots()) {
    const fs::path dir = fs::path(root) / "experiments" / "suites";
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) continue;
    for (const auto& entry : fs::directory_iterator(dir))
      if (entry.path().extension() == ".json") names.push_back(entry.path().stem().string());
    break;  // the first root that has suites
  }
  std::sort(names.begin(), names.end());
  return names;
}

std::string resolve_suite_path(const std::string& name_or_file) {
  if (fs::is_regular_file(name_or_file)) return name_or_file;
  for (const std::string& root : data_roots()) {
    const fs::path p = fs::path(root) / "experiments" / "suites" / (name_or_file + ".json");
    if (fs::is_regular_file(p)) return p.string();
  }
  std::string known;
  for (const std::string& n : builtin_suite_names()) known += (known.empty() ? "" : ", ") + n;
  throw InputError(name_or_file, "no such suite file or built-in suite (built-in: " + known + ")");
}

}  // namespace dv
