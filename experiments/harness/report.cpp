// Markdown reports of result folders (report.h).
#include "experiments/harness/report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <unistd.h>

#include "core/error.h"
#include "core/json_reader.h"
#include "core/number_text.h"
#include "experiments/harness/aa_controls.h"
#include "experiments/harness/driver.h"
#include "experiments/harness/durable_file.h"
#include "experiments/harness/findings.h"
#include "experiments/harness/lossy.h"
#include "experiments/harness/pareto.h"
#include "experiments/harness/plot_fits.h"
#include "experiments/harness/recorded_runs.h"
#include "experiments/harness/rows.h"
#include "experiments/harness/run_journal.h"
#include "experiments/harness/shape_verdict.h"
#include "experiments/harness/suite_file.h"
#include "strategies/shadow/strategy_catalog.h"

namespace dv {

namespace fs = std::filesystem;

namespace {

std::string cell(const nlohmann::json& v) {
  if (v.is_string()) return v.get<std::string>();
  if (v.is_number()) return table_text(v.get<double>(), 4);
  if (v.is_null()) return "–";
  if (v.is_array() && v.size() == 2 && v[0].is_number() && v[1].is_number())
    return cell(v[0]) + "–" + cell(v[1]);  // a range the paper prints ("2–3" fps)
  return v.dump();
}

// A paper's cell with its number as transcribed (10.166 stays 10.166; JSON's shortest form).
std::string paper_cell(const nlohmann::json& v) {
  if (v.is_number()) return v.dump();
  if (v.is_array() && v.size() == 2 && v[0].is_number() && v[1].is_number())
    return v[0].dump() + "–" + v[1].dump();
  return cell(v);
}

// Runs the plot script; returns an empty string when plots were made, else why not.
std::string draw_plots(const fs::path& dir) {
  fs::path script;
  for (const std::string& root : data_roots()) {
    const fs::path p = fs::path(root) / "experiments" / "harness" / "plot_suite.py";
    if (fs::is_regular_file(p)) {
      script = p;
      break;
    }
  }
  if (script.empty()) return "plot script experiments/harness/plot_suite.py not found";
  // Debian's interpreter first: python3-matplotlib installs there, while a python3 earlier
  // in PATH (pyenv, venv) may lack it.
  std::vector<std::string> pythons{"python3"};
  if (fs::exists("/usr/bin/python3")) pythons.insert(pythons.begin(), "/usr/bin/python3");
  // The strategies' families and colours, as `deepvox list --json` prints them.
  const fs::path catalog =
      fs::temp_directory_path() / ("deepvox-catalog-" + std::to_string(getpid()) + ".json");
  std::ofstream(catalog) << strategy_catalog_json().dump(1) << "\n";
  struct RemoveAtEnd {
    fs::path path;
    ~RemoveAtEnd() {
      std::error_code ec;
      fs::remove(path, ec);
    }
  } remove_catalog{catalog};
  std::string why = "python3 is not installed";
  for (const std::string& python : pythons) {
    const std::string cmd = python + " '" + script.string() + "' '" + dir.string() +
                            "' --catalog '" + catalog.string() + "' 2>&1";
    FILE* pipe = popen(cmd.c_str(), "r");
    if (!pipe) continue;
    std::string out;
    char buf[512];
    while (size_t n = fread(buf, 1, sizeof buf, pipe)) out.append(buf, n);
    const int status = pclose(pipe);
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    if (code == 0) return "";
    if (code == 3)
      why = "python3-matplotlib is not installed";
    else if (code != 127)
      return "the plot script failed: " + out.substr(0, 400);
  }
  return why;
}

void write_table(std::ostream& md, const std::vector<std::string>& header,
                 const std::vector<std::vector<std::string>>& body) {
  md << "|";
  for (const std::string& h : header) md << " " << h << " |";
  md << "\n|";
  for (size_t i = 0; i < header.size(); ++i) md << " --- |";
  md << "\n";
  for (const auto& row : body) {
    md << "|";
    for (const std::string& c : row) md << " " << c << " |";
    md << "\n";
  }
  md << "\n";
}

// The selection behind one value cell of a mapped paper table: the map's `where`, the row's and
// the column's selectors, and the row's column (or the column's own); false when unmapped.
bool cell_selection(const Json& map, size_t row, size_t column, std::string& selector,
                    Column& metric) {
  const Json& r = map["rows"][row];
  const Json& c = map["columns"][column];
  if (r.is_null() || c.is_null()) return false;
  const std::string column_selector =
      c.is_string() ? c.get<std::string>() : c[0].get<std::string>();
  metric = parse_column(c.is_array() ? c[1].get<std::string>() : r[1].get<std::string>());
  selector = map.value("where", "") + " " + r[0].get<std::string>() + " " + column_selector;
  return true;
}

// Ours for one value cell of a mapped paper table: the mean of the cell's column over the items
// of its selection; empty when unmapped or nothing matches.
std::string our_cell(const Json& map, size_t row, size_t column,
                     const std::map<int, std::vector<const Row*>>& items,
                     const std::map<int, std::string>& lossy) {
  std::string selector;
  Column metric;
  if (!cell_selection(map, row, column, selector, metric)) return "";
  const SelectionMean m = selection_mean(selector, metric, items);
  if (!m.items) return "";
  const bool lost = std::any_of(m.indices.begin(), m.indices.end(),
                                [&](int index) { return lossy.count(index) > 0; });
  return table_text(m.mean, 4) + (lost ? kLossyMark : "");
}

// The shape table of a mapped paper table with a "shape" entry (suite-format.md): the paper's
// ratios beside ours with our intervals (between two value columns of a row: across the sweep;
// between two rows of a column: within the table) and the overhead above the no-shadow frame,
// then the suite's sentence on what the machine change predicts. Each row gets a verdict
// (shape_verdict.h: the paper's value inside our interval, within the shape's band, or differs;
// not comparable) and the table one sentence naming which rows reproduce and at what loads.
// `runs`: every experiment's items, so that a baseline in another experiment can be selected
// (`experiment=NAME`).
void write_shape_table(std::ostream& md, const Json& t, const Json& map,
                       const std::string& experiment, const std::vector<RunView>& runs) {
  const Json& shape = map["shape"];
  const size_t labels = size_t(t.value("label_columns", 1));
  const Json& rows = t["rows"];
  const Json& columns = t["columns"];
  const auto row_name = [&](size_t r) {
    std::string name;
    for (size_t l = 0; l < labels; ++l) name += (l ? " " : "") + cell(rows[r][l]);
    return labels > 0 ? name : "row " + std::to_string(r + 1);
  };
  // A paper cell as a number: a range at its midpoint; with "paper_as": "ms_from_fps" a rate as
  // milliseconds (1000 / fps, a range's ends converted first), so its ratios are time ratios.
  const bool from_fps = map.value("paper_as", "") == "ms_from_fps";
  const auto paper_value = [&](const Json& v) {
    const auto as_time = [&](double x) { return from_fps ? 1000.0 / x : x; };
    if (v.is_array() && v.size() == 2 && v[0].is_number() && v[1].is_number())
      return 0.5 * (as_time(v[0].get<double>()) + as_time(v[1].get<double>()));
    return v.is_number() ? as_time(v.get<double>()) : std::nan("");
  };
  const auto column_name = [&](size_t c) { return cell(columns[labels + c]); };
  const double band = shape.value("band", kDefaultShapeBand);
  std::vector<std::vector<std::string>> body;
  std::vector<ShapeRow> verdicts;
  // One line: the paper's two numbers (their ratio or difference) beside our comparison of two
  // selections, and the verdict.
  const auto line = [&](const std::string& what, double paper_first, double paper_second,
                        const std::string& first_selector, const Column& first,
                        const std::string& second_selector, const Column& second, bool difference) {
    const double paper = difference ? paper_first - paper_second : paper_first / paper_second;
    const Comparison c =
        compare_selections("experiment=" + experiment + " " + first_selector, first,
                           second_selector, second, runs, seed_of(experiment + what), difference);
    // Without an interval: our point value where both sides were measured, and why.
    std::string ours = c.verdict;
    if (c.has_interval)
      ours = interval_text(c.interval);
    else if (c.first_items && c.second_items && (difference || c.second != 0.0))
      ours = (difference ? table_text(c.first - c.second, 4)
                         : table_text(c.first / c.second, 4) + "x") +
             ", " + c.verdict;
    const ShapeVerdict verdict = shape_verdict(paper_first, paper_second, c, difference, band);
    body.push_back({what,
                    std::isnan(paper) || std::isinf(paper)
                        ? "–"
                        : table_text(paper, 4) + (difference ? "" : "x"),
                    ours, c.basis.empty() ? "-" : c.basis, verdict.text});
    verdicts.push_back({what, verdict, c.first, c.second, is_time_metric(first.metric)});
  };
  const auto pairs = [&](const char* key, bool of_rows) {
    for (const Json& pair : shape.value(key, Json::array())) {
      const size_t a = pair[0].get<size_t>(), b = pair[1].get<size_t>();
      const size_t lines = of_rows ? columns.size() - labels : rows.size();
      for (size_t k = 0; k < lines; ++k) {
        const size_t ra = of_rows ? a : k, rb = of_rows ? b : k;
        const size_t ca = of_rows ? k : a, cb = of_rows ? k : b;
        std::string sa, sb;
        Column ma, mb;
        if (!cell_selection(map, ra, ca, sa, ma) || !cell_selection(map, rb, cb, sb, mb)) continue;
        const std::string what =
            of_rows ? row_name(ra) + " / " + row_name(rb) + ", " + column_name(ca)
                    : row_name(ra) + ", " + column_name(ca) + " / " + column_name(cb);
        line(what, paper_value(rows[ra][labels + ca]), paper_value(rows[rb][labels + cb]), sa, ma,
             "experiment=" + experiment + " " + sb, mb, false);
      }
    }
  };
  pairs("column_pairs", false);
  pairs("row_pairs", true);
  if (shape.contains("baseline")) {
    const Json& base = shape["baseline"];
    const Column base_column = parse_column(base["column"].get<std::string>());
    for (const Json& r : base["rows"]) {
      const size_t row = r.get<size_t>();
      for (size_t c = 0; c + labels < columns.size(); ++c) {
        std::string selector;
        Column metric;
        if (!cell_selection(map, row, c, selector, metric)) continue;
        line(row_name(row) + ", " + column_name(c) + " − the no-shadow frame",
             paper_value(rows[row][labels + c]), base["paper"].get<double>(), selector, metric,
             base["selector"].get<std::string>(), base_column, true);
      }
    }
  }
  if (body.empty()) return;
  md << "Shape (ratios within the table and across the sweep, paper beside ours with our 95 % "
        "interval; the paper's ranges at their midpoints"
     << (from_fps ? ", its rates as times (1000 / fps)" : "")
     << (shape.contains("baseline")
             ? "; overhead above the no-shadow frame: the paper's " +
                   table_text(shape["baseline"]["paper"].get<double>(), 4) + " ms (" +
                   shape["baseline"].value("source", std::string("paper")) + ") against ours, `" +
                   shape["baseline"]["selector"].get<std::string>() + "`"
             : std::string())
     << "; verdict: the paper's value inside our interval, or within ±"
     << significant_text(100.0 * band, 2)
     << " % of it (the interval widened by the band), else differs; not comparable where a side "
        "is missing or 0 against 0):\n\n";
  write_table(md, {"ratio", "paper", "ours [95 % interval]", "interval rests on", "verdict"}, body);
  md << "Shape verdicts: " << shape_sentence(verdicts, band) << "\n\n";
  if (shape.contains("machine")) md << "Machine change: " << cell(shape["machine"]) << "\n\n";
}

// A paper rate (a number or a [low, high] range in fps) as milliseconds, 1000 / fps: a range's
// ends swap.
Json milliseconds_from_fps(const Json& v) {
  if (v.is_array()) return Json::array({1000.0 / v[1].get<double>(), 1000.0 / v[0].get<double>()});
  return 1000.0 / v.get<double>();
}

// A paper table file (docs/paper-tables.md) as printed, with both machines named; with a map
// (suite-format.md) every mapped value cell shows "paper / ours", the paper's rate also in ms
// where the map says "paper_as": "ms_from_fps".
void write_paper_table(std::ostream& md, const std::string& file, const std::string& our_machine,
                       const Json& map, const std::map<int, std::vector<const Row*>>& items,
                       const std::map<int, std::string>& lossy, const std::string& experiment,
                       const std::vector<RunView>& all_runs) {
  Json t;
  try {
    t = parse_json_file(file);
  } catch (const std::exception& ex) {
    md << "\nPaper table " << file << " could not be read: " << ex.what() << "\n\n";
    return;
  }
  md << "\nPaper: **" << cell(t.value("source", Json(file))) << "**"
     << (t.contains("caption") ? " — " + cell(t["caption"]) : "") << "\n\n";
  md << "- paper machine: " << cell(t.value("machine", Json("not stated"))) << "\n";
  md << "- our machine: " << our_machine << "\n";
  if (t.contains("units") && t["units"].is_object()) {
    md << "- units:";
    for (const auto& [key, unit] : t["units"].items())
      md << " " << (key == "*" ? "every value" : key) << " = " << cell(unit) << ";";
    md << "\n";
  }
  const size_t labels = size_t(t.value("label_columns", 1));
  const Json& rows = t.value("rows", Json::array());
  const size_t values = t.value("columns", Json::array()).size() - labels;
  const bool beside =
      !map.is_null() && map["rows"].size() == rows.size() && map["columns"].size() == values;
  if (!map.is_null() && !beside)
    md << "- the suite's map of this table does not fit its rows and columns: ours not shown\n";
  const bool as_ms = beside && map.value("paper_as", "") == "ms_from_fps";
  if (as_ms)
    md << "- the paper's rates converted: `fps = ms` with ms = 1000 / fps (a range's ends swap), "
          "ours in ms\n";
  if (beside)
    md << "- cells: paper / ours (ours: the mean over our items matching `" +
              map.value("where", "") +
              "`, the row's and the column's selector; the paper "
              "alone where it prints nothing or nothing is mapped or measured)\n";
  md << "\n";
  std::vector<std::string> header;
  for (const auto& h : t.value("columns", Json::array())) header.push_back(cell(h));
  if (beside)
    for (size_t c = 0; c < values; ++c)
      if (const Json& m = map["columns"][c]; m.is_string() && !m.get<std::string>().empty())
        header[labels + c] += " [" + m.get<std::string>() + "]";
      else if (m.is_array())
        header[labels + c] +=
            " [" + (m[0].get<std::string>().empty() ? "" : m[0].get<std::string>() + " ") +
            m[1].get<std::string>() + "]";
  std::vector<std::vector<std::string>> body;
  for (size_t i = 0; i < rows.size(); ++i) {
    std::vector<std::string> line;
    for (size_t k = 0; k < rows[i].size(); ++k) {
      std::string text = paper_cell(rows[i][k]);
      if (beside && k >= labels && !rows[i][k].is_null()) {
        if (as_ms) text += " fps = " + cell(milliseconds_from_fps(rows[i][k])) + " ms";
        const std::string ours = our_cell(map, i, k - labels, items, lossy);
        if (!ours.empty()) text += " / " + ours;
      }
      line.push_back(text);
    }
    if (beside && labels > 0 && !map["rows"][i].is_null()) {
      const std::string selector = map["rows"][i][0].get<std::string>();
      line[labels - 1] += " [ours: " + (selector.empty() ? "" : selector + " ") +
                          map["rows"][i][1].get<std::string>() + "]";
    }
    body.push_back(std::move(line));
  }
  if (!header.empty()) write_table(md, header, body);
  if (beside && body_has_mark(body)) md << "\n" << kLossyMeaning << ".\n";
  if (beside && map.contains("shape")) write_shape_table(md, t, map, experiment, all_runs);
  if (t.contains("notes"))
    md << "<details><summary>paper table notes (setup mapping, formulas, ambiguities)</summary>\n\n"
       << cell(t["notes"]) << "\n\n</details>\n\n";
}

void write_findings(std::ostream& md, const ExperimentSpec& e, const std::vector<RunView>& runs,
                    const TieBands& tie_bands, const PracticalBands& practical_bands) {
  const std::vector<FindingResult> results =
      evaluate_findings(e.findings, runs, tie_bands, practical_bands);
  if (results.empty()) return;
  md << "\nFindings (effect: first side / second side, or their difference for probe errors, "
        "with its 95 % interval: Student's t over the per-run effects, a bootstrap over the "
        "points for probe errors; confirmed: the interval entirely on the claimed side, "
        "refuted: entirely on the other, tie: it holds no effect (for differences the suite's "
        "practical band of the metric); a trend tests every step of its sweep; the timer: the "
        "time metric that decides the claim, none for a quantity no timer measures):\n\n";
  std::vector<std::vector<std::string>> body;
  for (const FindingResult& f : results)
    body.push_back({f.claim, f.lower_text, f.lower_items ? table_text(f.lower, 4) : "-",
                    f.than_text.empty() ? "-" : f.than_text,
                    f.than_items ? table_text(f.than, 4) : "-", f.effect.empty() ? "-" : f.effect,
                    f.basis.empty() ? "-" : f.basis, f.timer.empty() ? "-" : f.timer, f.verdict,
                    f.explanation});
  write_table(
      md,
      {"claim", "ours (lower?)", "value", "than", "value", "effect [95 % interval]",
       "interval rests on", "timer", "verdict", "why (from the data, then the suite's reading)"},
      body);
}

std::vector<std::string> column_list(const Json& v) {
  if (v.is_string()) return {v.get<std::string>()};
  std::vector<std::string> out;
  for (const auto& c : v) out.push_back(c.get<std::string>());
  return out;
}

// Per scene and (error, cost) pair: the Pareto front as a table and the regime sentence. A/A
// copies are left out (the same configuration twice would crowd the front with itself).
void write_pareto(std::ostream& md, const ExperimentSpec& e,
                  const std::map<int, std::vector<const Row*>>& items,
                  const std::map<int, std::string>& lossy) {
  if (e.pareto.is_null()) return;
  std::vector<std::string> scenes;
  for (const auto& [index, rows] : items)
    if (std::find(scenes.begin(), scenes.end(), rows.front()->scene) == scenes.end())
      scenes.push_back(rows.front()->scene);
  for (const std::string& scene : scenes)
    for (const std::string& error : column_list(e.pareto["error"]))
      for (const std::string& cost : column_list(e.pareto["cost"])) {
        std::vector<ParetoPoint> points;
        for (const auto& [index, rows] : items) {
          if (rows.front()->scene != scene || is_aa_copy(rows.front()->params)) continue;
          const Row* x = find_row(rows, parse_column(cost));
          const Row* y = find_row(rows, parse_column(error));
          if (x && y)
            points.push_back({x->value, y->value,
                              item_label(*rows.front()) + (lossy.count(index) ? kLossyMark : "")});
        }
        const std::vector<size_t> front = pareto_front(points);
        md << "\nPareto front on `" << scene << "`, " << error << " vs " << cost << " ("
           << front.size() << " of " << points.size() << " points):\n\n";
        std::vector<std::vector<std::string>> body;
        for (size_t i : front)
          body.push_back(
              {points[i].label, table_text(points[i].cost, 4), table_text(points[i].error, 4)});
        write_table(md, {"strategy and params", cost, error}, body);
        if (body_has_mark(body)) md << "\n" << kLossyMeaning << ".\n";
        md << pareto_regimes(points, front, cost, error) << "\n\n";
      }
}

// The experiment's plots in the order and with the captions plot_suite.py wrote to
// plots/plots.json, numbered; PNGs it does not list (a folder drawn by an older script) after
// them, by name.
void write_plots(std::ostream& md, const fs::path& dir, const std::string& experiment) {
  Json index = Json::array();
  try {
    if (fs::exists(dir / "plots" / "plots.json"))
      index = parse_json_file((dir / "plots" / "plots.json").string());
  } catch (const std::exception&) {
    // unreadable (a folder copied half-way): the PNGs by name below
  }
  std::set<std::string> listed, rest;
  int number = 0;
  for (const Json& p : index) {
    if (!p.is_object() || p.value("experiment", "") != experiment) continue;
    const std::string file = p.value("file", "");
    if (!fs::exists(dir / "plots" / file) || !listed.insert(file).second) continue;
    md << "\n**Plot " << experiment << "." << ++number << "** (`plots/" << file
       << "`): " << p.value("caption", "") << "\n\n![" << file << "](plots/" << file << ")\n"
       << fits_table(p.value("fits", Json()));
  }
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir / "plots", ec))
    if (const std::string f = entry.path().filename().string();
        f.rfind(experiment + "_", 0) == 0 && !listed.count(f))
      rest.insert(f);
  for (const std::string& p : rest) md << "![" << p << "](plots/" << p << ")\n";
  md << "\n";
}

// `shown`: the rows the tables show (rows_over_runs); `runs`: each run's, for the findings.
void write_experiment(std::ostream& md, const fs::path& dir, const ExperimentSpec& e,
                      const RunView& shown, const std::vector<RunView>& runs,
                      const std::vector<RunView>& all_runs, const std::string& our_machine,
                      const PracticalBands& practical_bands) {
  const std::map<int, std::vector<const Row*>>& items = shown.items;
  md << "## " << e.name << " (" << e.kind << ")\n\n";
  if (!e.description.empty()) md << e.description << "\n\n";
  if (items.empty()) {
    md << "Not run here (other shard, --only, or interrupted).\n\n";
    return;
  }
  std::vector<Column> columns;
  const std::vector<std::string> names =
      e.columns.empty() ? driver_registry().create(e.kind)->default_columns() : e.columns;
  for (const std::string& c : names) columns.push_back(parse_column(c));
  std::vector<std::string> header;
  if (e.scenes.size() > 1) header.push_back("scene");
  header.insert(header.end(), {"strategy", "params"});
  for (const Column& c : columns) {
    std::string unit;
    for (const auto& [index, rows] : items)
      if (const Row* r = find_row(rows, c); r && unit.empty()) unit = r->unit;
    header.push_back(c.metric + (c.stat.empty() ? "" : " " + c.stat) +
                     (unit.empty() || unit == "1" ? "" : " (" + unit + ")"));
  }
  const std::map<int, std::string> lossy = lossy_items(runs);
  std::vector<std::vector<std::string>> body;
  for (const auto& [index, rows] : items) {
    const Row& first = *rows.front();
    std::vector<std::string> line;
    if (e.scenes.size() > 1) line.push_back(first.scene);
    line.push_back(first.strategy);
    line.push_back((first.params.empty() ? "-" : first.params) +
                   (lossy.count(index) ? kLossyMark : ""));
    const Row* failed = find_row(rows, {"failed", "value"});
    const Row* skipped = find_row(rows, {"skipped", "value"});
    for (const Column& c : columns) {
      const Row* r = find_row(rows, c);
      line.push_back(failed ? "failed" : skipped ? "skipped" : r ? table_text(r->value, 4) : "-");
    }
    body.push_back(std::move(line));
  }
  write_table(md, header, body);
  for (const auto& [index, rows] : items)
    for (const char* what : {"failed", "skipped"})
      if (const Row* r = find_row(rows, {what, "value"}))
        md << "- item " << index << " (" << r->strategy << " " << r->params << ") " << what << ": "
           << r->note << "\n";
  write_lossy_list(md, items, lossy);
  if (!e.paper.is_null()) {
    md << "\nPaper values"
       << (e.paper.contains("source") ? " (" + cell(e.paper["source"]) + ")" : "") << ":\n\n";
    std::vector<std::string> paper_header;
    for (const auto& h : e.paper["columns"]) paper_header.push_back(cell(h));
    std::vector<std::vector<std::string>> paper_body;
    for (const auto& r : e.paper["rows"]) {
      std::vector<std::string> line;
      for (const auto& v : r) line.push_back(paper_cell(v));
      paper_body.push_back(std::move(line));
    }
    write_table(md, paper_header, paper_body);
  }
  for (size_t p = 0; p < e.paper_files.size(); ++p)
    write_paper_table(md, e.paper_files[p], our_machine,
                      p < e.paper_maps.size() ? e.paper_maps[p] : Json(), items, lossy, e.name,
                      all_runs);
  // The experiment's A/A controls: their false-positive rate and the tie bands the findings use.
  const AaControls aa = measure_aa_controls(runs);
  if (!aa.pairs.empty())
    md << "\nA/A controls (`aa_duplicates`): " << aa_rate_text(aa)
       << "; tie bands from the A/A spread: " << tie_bands_text(aa) << "\n";
  write_findings(md, e, runs, aa.tie_bands, practical_bands);
  write_pareto(md, e, items, lossy);
  // Image strip: the reference, then each render with its difference below.
  std::string reference;
  std::vector<std::string> labels, renders, diffs;
  for (const auto& [index, rows] : items) {
    const Row* ref = find_row(rows, {"image", "reference"});
    const Row* render = find_row(rows, {"image", "render"});
    const Row* diff = find_row(rows, {"image", "difference"});
    if (!render) continue;
    if (ref && reference.empty()) reference = ref->note;
    labels.push_back(item_label(*render) + (lossy.count(index) ? kLossyMark : ""));
    renders.push_back("![](" + render->note + ")");
    diffs.push_back(diff ? "![](" + diff->note + ")" : "");
  }
  if (!renders.empty()) {
    md << "\nImages (second row: largest channel difference to the reference x4):\n\n";
    labels.insert(labels.begin(), "reference (exact oracle)");
    renders.insert(renders.begin(), reference.empty() ? "" : "![](" + reference + ")");
    diffs.insert(diffs.begin(), "");
    write_table(md, labels, {renders, diffs});
  }
  write_plots(md, dir, e.name);
}

// "- scale-out: 2 GPUs on 1 host (node1); missing shards: 2 of 2" for a merged folder.
// The machine's state at the start (run_metadata.h's machine_state; "unknown" for what a run
// could not read, and for folders written before it was recorded). A CPU run says so instead of
// a GPU line of unknowns, and names a GPU it read but did not use.
std::string machine_lines(const Json& run) {
  const Json machine = run.value("machine", Json::object());
  const auto at = [&](const char* key) {
    return machine.contains(key) ? cell(machine[key]) : std::string("unknown");
  };
  const std::string os = "- OS: " + at("os") + ", kernel " + at("kernel") + "\n";
  const bool cpu_run = run.value("backend", Json("")) == "cpu";
  if (cpu_run && at("nvidia_driver") == "unknown") return "- GPU: none used (CPU run)\n" + os;
  const auto mhz = [&](const char* now, const char* max) {
    return at(now) + " of " + at(max) + " MHz";
  };
  std::string cuda;
  if (run.contains("cuda")) {
    const Json& c = run["cuda"];
    const char* api = c.contains("driver_api_version") ? "driver_api_version" : "driver_version";
    cuda = " (CUDA driver API " + cell(c.value(api, Json("unknown"))) + ", runtime " +
           cell(c.value("runtime_version", Json("unknown"))) + ")";
  }
  return std::string(cpu_run ? "- GPU (present, not used: CPU run): " : "- GPU: ") +
         "NVIDIA driver " + at("nvidia_driver") + cuda + ", SM clock " +
         mhz("sm_clock_mhz", "sm_clock_max_mhz") + ", memory clock " +
         mhz("memory_clock_mhz", "memory_clock_max_mhz") + ", persistence mode " +
         at("persistence_mode") + ", compute mode " + at("compute_mode") +
         ", shared with other compute processes: " + at("gpu_shared") + "\n" + os;
}

std::string scale_out_line(const Json& meta) {
  std::string hosts;
  for (const Json& h : meta["scale_out"]["hosts"]) hosts += (hosts.empty() ? "" : ", ") + cell(h);
  std::string line = "- scale-out: " + cell(meta["scale_out"]["summary"]) + " (" + hosts + ")";
  if (meta.contains("missing_shards")) {
    std::string missing;
    for (const Json& i : meta["missing_shards"])
      missing += (missing.empty() ? "" : ", ") + i.dump();
    line += "; missing shards: " + missing + " of " +
            std::to_string(meta["merged_from"].size() + meta["missing_shards"].size());
  }
  return line + "\n";
}

// "3, 4, 7" for item indices.
std::string item_list(const std::vector<int>& items) {
  std::string out;
  for (int i : items) out += (out.empty() ? "" : ", ") + std::to_string(i);
  return out;
}

// The status line: complete, interrupted (Ctrl-C) or partial (killed, stopped, being written),
// with how to resume; resumed and mixed runs (--resume, --resume --force) say so.
std::string status_lines(const RunState& state, const fs::path& dir) {
  const Json& meta = state.meta;
  const std::string resume = "resume: `deepvox suite " + meta.value("suite_file", "SUITE") +
                             " --resume " + dir.string() + "`";
  const std::string run_state = meta.value("state", "finished");
  const int items = meta.value("items", 0);
  std::ostringstream md;
  md << "- status: ";
  if (state.journaled && !state.finished && run_state != "interrupted") {
    md << "PARTIAL: " << state.done << " of " << items << " experiments complete, "
       << state.missing.size() << " missing ("
       << (state.locked             ? "a deepvox process is still writing the folder"
           : run_state == "stopped" ? "the run stopped: " + meta.value("stopped_by", "")
                                    : "the run was killed before it ended")
       << "); " << resume;
  } else {
    md << (meta.value("interrupted", false) ? "interrupted after " : "ran ") << state.done << " of "
       << items << " experiments" << (meta.contains("merged_from") ? " (merged shards)" : "");
    if (meta["shard"]["count"].get<int>() > 1)
      md << ", shard " << cell(meta["shard"]["index"]) << "/" << cell(meta["shard"]["count"]);
    md << ", " << state.failed << " failed, " << state.skipped << " skipped (not for this backend)";
    if (meta.value("interrupted", false) && state.journaled) md << "; " << resume;
    if (!state.missing.empty())
      md << "; PARTIAL: " << state.missing.size() << " planned experiments missing (below)";
  }
  md << "\n";
  const Json attempts = meta.value("attempts", Json::array());
  if (attempts.size() > 1)
    md << "- resumed: " << attempts.size() - 1 << " time" << (attempts.size() > 2 ? "s" : "")
       << " (meta.json lists every attempt)\n";
  for (size_t a = 1; a < attempts.size(); ++a) {
    if (!attempts[a].contains("forced")) continue;
    std::vector<int> ran;
    for (const auto& [item, attempt] : state.attempt_of)
      if (attempt == int(a + 1)) ran.push_back(item);
    std::string what;
    for (const Json& w : attempts[a]["forced"]) what += (what.empty() ? "" : " and ") + cell(w);
    md << "- MIXED (--resume --force): items " << (ran.empty() ? "none" : item_list(ran))
       << " ran with another " << what << " (git " << cell(attempts[a]["git_sha"])
       << ", suite hash " << cell(attempts[a]["suite_hash"]) << ") than the rest (git "
       << cell(attempts[0]["git_sha"]) << ", suite hash " << cell(attempts[0]["suite_hash"])
       << ")\n";
  }
  return md.str();
}

// The planned items without complete rows, each named.
std::string missing_list(const RunState& state, const Suite& suite) {
  if (state.missing.empty()) return "";
  std::map<int, std::string> names;
  for (const RunItem& item : expand_suite(suite)) names[item.index] = item.describe();
  std::ostringstream md;
  md << "Missing (" << state.missing.size() << " planned experiment"
     << (state.missing.size() == 1 ? "" : "s") << " without complete rows):\n\n";
  for (int i : state.missing)
    md << "- item " << i << ": " << (names.count(i) ? names[i] : "not in suite.json") << "\n";
  md << "\n";
  return md.str();
}

// An item's samples/<item>.json, null when the folder has none (written before samples/, or a
// driver without samples).
Json read_samples(const fs::path& dir, int item) {
  const fs::path file = dir / "samples" / (std::to_string(item) + ".json");
  if (!fs::is_regular_file(file)) return Json();
  return parse_json_file(file.string());
}

// How the runs ordered their items (meta.json "order"; folders from before it: the suite's).
std::string order_text(const std::vector<RunState>& states) {
  std::string seeds;
  size_t permuted = 0;
  for (const RunState& s : states) {
    const Json order = s.meta.value("order", Json::object());
    if (order.value("protocol", "") != "replicate") continue;
    ++permuted;
    seeds += (seeds.empty() ? "" : ", ") + order["seed"].dump();
  }
  if (permuted == 0) return "the suite's, the same in every run";
  return "replicate protocol in " + std::to_string(permuted) + " of " +
         std::to_string(states.size()) + " runs: each run's items permuted with its own seed (" +
         seeds +
         "; meta.json \"order\"), the two sides of each comparison claim in adjacent pairs, "
         "ABBA";
}

// "probe_error_all:mean ±0.002, image_rmse ±0.001 (suite practical_bands)", or none.
std::string practical_bands_text(const PracticalBands& bands) {
  if (bands.empty()) return "none stated (suite practical_bands): differences tie only at 0";
  std::string out;
  for (const auto& [column, band] : bands)
    out += (out.empty() ? "" : ", ") + column + " ±" + significant_text(band, 3);
  return out + " (suite practical_bands, in each metric's unit)";
}

}  // namespace

void build_report(const std::string& folder) {
  const fs::path dir(folder);
  const RunState state = read_run_state(dir);
  const Json& meta = state.meta;
  const Suite parsed =
      parse_recorded_suite(read_file_text(dir / "suite.json"), (dir / "suite.json").string());
  Suite suite = meta.value("smoke", false) ? smoke_suite(parsed) : parsed;
  // Paper tables named beside the suite file as run (not in the result folder): look there too.
  for (ExperimentSpec& e : suite.experiments)
    for (std::string& paper : e.paper_files)
      if (!fs::exists(paper)) paper = resolve_data_file(paper, meta.value("suite_file", ""));
  // The runs the findings' intervals rest on: this folder, then those runs.json names.
  std::vector<RunState> states{state};
  for (const fs::path& other : recorded_runs(dir, suite.name, meta.value("suite_hash", "")))
    states.push_back(read_run_state(other));
  std::vector<std::vector<RunView>> by_experiment(suite.experiments.size(),
                                                  std::vector<RunView>(states.size()));
  // What the tables and plots show (rows_over_runs), and the file the plot script reads.
  const std::vector<Row> shown_rows = rows_over_runs(states);
  std::vector<RunView> shown(suite.experiments.size());
  for (const Row& r : shown_rows)
    for (size_t e = 0; e < suite.experiments.size(); ++e)
      if (suite.experiments[e].name == r.experiment) shown[e].items[r.item].push_back(&r);
  const fs::path shown_file = dir / "rows_over_runs.csv";
  std::error_code no_file;
  fs::remove(shown_file, no_file);
  if (states.size() > 1) write_rows_csv(shown_file.string(), shown_rows);
  std::vector<RunView> all_runs(states.size());
  for (size_t run = 0; run < states.size(); ++run)
    for (const Row& r : states[run].rows) {
      RunView& all = all_runs[run];
      all.items[r.item].push_back(&r);
      if (!all.samples.count(r.item)) all.samples[r.item] = read_samples(states[run].dir, r.item);
      for (size_t e = 0; e < suite.experiments.size(); ++e)
        if (suite.experiments[e].name == r.experiment) {
          by_experiment[e][run].items[r.item].push_back(&r);
          by_experiment[e][run].samples[r.item] = all.samples[r.item];
        }
    }

  bool plots_asked = false;
  for (const ExperimentSpec& e : suite.experiments)
    plots_asked |= !e.plots.empty() || !e.pareto.is_null();
  const std::string plot_problem = plots_asked ? draw_plots(dir) : "none asked for";
  std::ostringstream md;
  const Json& run = meta["run"];
  const std::string our_machine = (run.contains("device") ? cell(run["device"]) + " (GPU), " : "") +
                                  cell(run["cpu_model"]) + " (CPU), backend " +
                                  cell(run["backend"]);
  md << "# Suite `" << suite.name << "`\n\n";
  if (!suite.description.empty()) md << suite.description << "\n\n";
  md << "- when: " << cell(run["utc_time"]) << ", git " << cell(run["git_sha"]) << ", "
     << cell(run["build_type"]) << " build, " << cell(run["compiler"]) << "\n";
  md << "- backend: " << cell(run["backend"]) << " on "
     << (run.contains("device") ? cell(run["device"]) + ", " : "") << cell(run["cpu_model"]) << ", "
     << cell(run["cpu_threads"]) << " threads\n";
  md << machine_lines(run);
  if (meta.value("smoke", false))
    md << "- size: SMOKE (each experiment's `smoke` overrides: a correctness run, not a "
          "measurement)\n";
  md << "- timings: one warm-up, then " << cell(meta["repeat"])
     << " repetitions, median (min, max in rows.csv; every repetition in samples/)\n";
  if (states.size() > 1)
    md << "- tables and plots: over the " << states.size()
       << " runs: each cell the median of the runs' values (a timing: of their medians), "
          "whiskers the lowest to the highest run median (rows_over_runs.csv)\n";
  md << "- findings' intervals rest on " << states.size() << " independent process run"
     << (states.size() == 1 ? " (this folder)" : "s (this folder and those runs.json names)")
     << (states.size() < 2 ? "; a t-interval over runs needs at least 2, so timings and values "
                             "per run get no verdict (deepvox suite NAME --runs 5)"
                           : "; 95 % t-intervals over the per-run effects")
     << "\n";
  md << "- item order: " << order_text(states) << "\n";
  md << "- A/A false-positive rate: " << aa_rate_text(measure_aa_controls(all_runs)) << "\n";
  md << "- practical bands (a difference whose interval lies within one is a tie): "
     << practical_bands_text(suite.practical_bands) << "\n";
  md << status_lines(state, dir);
  if (meta.contains("scale_out")) md << scale_out_line(meta);
  md << "- plots: " << (plot_problem.empty() ? "plots/ (matplotlib)" : "skipped: " + plot_problem)
     << "\n- files: rows.csv (one row per measurement), samples/ (every repetition and probe "
        "error), params.json (echoed parameters), meta.json, command.txt, runs.json (further "
        "runs, when there are)\n\n";
  md << missing_list(state, suite);
  std::ifstream command_in(dir / "command.txt");
  std::stringstream command;
  command << command_in.rdbuf();
  md << "Command (command.txt; a merged folder lists its shards' too):\n\n```\n"
     << command.str() << "```\n\n";
  for (size_t e = 0; e < suite.experiments.size(); ++e)
    write_experiment(md, dir, suite.experiments[e], shown[e], by_experiment[e], all_runs,
                     our_machine, suite.practical_bands);
  try {
    write_file_atomically(dir / "report.md", md.str());
  } catch (const ResultWriteError& e) {
    throw InputError((dir / "report.md").string(), std::string("cannot write report: ") + e.what());
  }
}

}  // namespace dv
