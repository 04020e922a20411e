// Findings evaluated against an experiment's rows, explained from the data (findings.h).
#include "experiments/harness/findings.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <sstream>

namespace dv {

namespace {

std::vector<std::string> words(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

bool term_matches(const std::string& term, const Row& r) {
  const size_t eq = term.find('=');
  if (eq == std::string::npos) return false;
  const std::string key = term.substr(0, eq), value = term.substr(eq + 1);
  if (key == "strategy") return r.strategy == value;
  if (key == "scene") return r.scene.find(value) != std::string::npos;
  for (const std::string& item : words(r.params))
    if (item == term) return true;
  return false;
}

std::string number(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

std::string signed_number(double v) {
  return (v >= 0 ? "+" : "") + number(v);
}

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// For a time column "X_ms": the passes "X.<...>_ms" of the deepest level present (so
// "generate.passes.write_ms" rather than their sum "generate.generation_ms"), each with the
// difference of its means (first side minus second); the largest named, and the part of the
// difference outside the passes (host work, allocation, synchronisation) when it is larger.
std::string pass_breakdown(const nlohmann::json& lower, const nlohmann::json& than,
                           const Column& column, double difference,
                           const std::map<int, std::vector<const Row*>>& items) {
  if (!ends_with(column.metric, "_ms")) return "";
  const std::string stem = column.metric.substr(0, column.metric.size() - 3) + ".";
  std::set<std::string> passes;
  size_t depth = 0;
  for (const auto& [index, rows] : items)
    for (const Row* r : rows)
      if (r->metric.rfind(stem, 0) == 0 && ends_with(r->metric, "_ms") &&
          r->stat == (column.stat.empty() ? "median" : column.stat)) {
        const size_t d = size_t(std::count(r->metric.begin(), r->metric.end(), '.'));
        if (d > depth) {
          passes.clear();
          depth = d;
        }
        if (d == depth) passes.insert(r->metric);
      }
  if (passes.empty()) return "";
  std::string largest;
  double largest_diff = 0.0, sum = 0.0;
  for (const std::string& p : passes) {
    const Column c{p, column.stat.empty() ? "median" : column.stat};
    const SelectionMean a = selection_mean(lower[0].get<std::string>(), c, items);
    const SelectionMean b = selection_mean(than[0].get<std::string>(), c, items);
    const double d = a.mean - b.mean;
    sum += d;
    if (largest.empty() || std::abs(d) > std::abs(largest_diff)) largest = p, largest_diff = d;
  }
  std::string out =
      "; largest pass difference " + largest + " " + signed_number(largest_diff) + " ms";
  const double outside = difference - sum;
  if (std::abs(outside) > std::abs(largest_diff))
    out += "; " + signed_number(outside) +
           " ms lies outside the timed passes (allocation, host work, synchronisation)";
  return out;
}

// For a median column: half the mean spread (max - min) of the two sides' repetitions; 0
// when the rows have no spread.
double half_spread(const nlohmann::json& lower, const nlohmann::json& than, const Column& column,
                   const std::map<int, std::vector<const Row*>>& items) {
  if (column.stat != "median") return 0.0;
  double sum = 0.0;
  for (const nlohmann::json* side : {&lower, &than}) {
    const std::string selector = (*side)[0].get<std::string>();
    const SelectionMean hi = selection_mean(selector, {column.metric, "max"}, items);
    const SelectionMean lo = selection_mean(selector, {column.metric, "min"}, items);
    if (!hi.items || !lo.items) return 0.0;
    sum += hi.mean - lo.mean;
  }
  return sum / 4.0;
}

}  // namespace

bool selector_matches(const std::string& selector, const Row& r) {
  for (const std::string& term : words(selector))
    if (!term_matches(term, r)) return false;
  return true;
}

SelectionMean selection_mean(const std::string& selector, const Column& column,
                             const std::map<int, std::vector<const Row*>>& items) {
  SelectionMean s;
  double sum = 0.0;
  for (const auto& [index, rows] : items) {
    if (rows.empty() || !selector_matches(selector, *rows.front())) continue;
    if (const Row* r = find_row(rows, column)) {
      sum += r->value;
      ++s.items;
    }
  }
  if (s.items) s.mean = sum / s.items;
  return s;
}

std::vector<FindingResult> evaluate_findings(const nlohmann::json& findings,
                                             const std::map<int, std::vector<const Row*>>& items) {
  std::vector<FindingResult> out;
  if (!findings.is_array()) return out;
  for (const auto& f : findings) {
    FindingResult r;
    r.claim = f["claim"].get<std::string>();
    r.why = f.value("why", "");
    r.lower_text = f["lower"][0].get<std::string>() + ": " + f["lower"][1].get<std::string>();
    r.than_text = f["than"][0].get<std::string>() + ": " + f["than"][1].get<std::string>();
    const Column lower_column = parse_column(f["lower"][1].get<std::string>());
    const SelectionMean lower =
        selection_mean(f["lower"][0].get<std::string>(), lower_column, items);
    const SelectionMean than = selection_mean(f["than"][0].get<std::string>(),
                                              parse_column(f["than"][1].get<std::string>()), items);
    r.lower = lower.mean;
    r.than = than.mean;
    r.lower_items = lower.items;
    r.than_items = than.items;
    if (!lower.items || !than.items) {
      r.verdict = "undecided (no measured item matches " +
                  std::string(!lower.items ? "the first" : "the second") + " side)";
      r.explanation = "-";
      out.push_back(std::move(r));
      continue;
    }
    const bool confirmed = lower.mean < than.mean;
    r.verdict = confirmed ? "confirmed" : "not confirmed";
    const double difference = lower.mean - than.mean;
    r.explanation = difference == 0.0
                        ? "both sides equal"
                        : "first side " + std::string(difference < 0.0 ? "lower" : "higher") +
                              " by " + number(std::abs(difference));
    if (than.mean != 0.0) r.explanation += " (" + number(lower.mean / than.mean) + "x)";
    if (f["lower"][1] == f["than"][1]) {
      const double noise = half_spread(f["lower"], f["than"], lower_column, items);
      if (std::abs(difference) < noise)
        r.explanation += "; within the repetitions' spread (+-" + number(noise) +
                         "): a tie, not a measured difference";
      r.explanation += pass_breakdown(f["lower"], f["than"], lower_column, difference, items);
    }
    const std::string reading = confirmed ? r.why : f.value("why_not", "");
    r.explanation += reading.empty() ? (confirmed ? "" : "; the cause is not explained here")
                                     : "; " + std::string(confirmed ? "reading: " : "") + reading;
    out.push_back(std::move(r));
  }
  return out;
}

}  // namespace dv
