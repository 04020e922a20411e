// Findings evaluated against an experiment's rows and samples: effect sizes with intervals,
// verdicts, and explanations from the data (findings.h).
#include "experiments/harness/findings.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <sstream>
#include <utility>

#include "core/number_text.h"
#include "experiments/harness/lossy.h"

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
  if (key == "experiment") return r.experiment == value;
  for (const std::string& item : words(r.params))
    if (item == term) return true;
  return false;
}

// For a time column "X_ms": the passes "X.<...>_ms" of the deepest level present (so
// "generate.passes.write_ms" rather than their sum "generate.generation_ms"), each with the
// difference of its means (first side minus second); the largest named, and the part of the
// difference outside the passes (host work, allocation, synchronisation) when it is larger.
std::string pass_breakdown(const std::string& lower, const std::string& than, const Column& column,
                           double difference, const std::map<int, std::vector<const Row*>>& items) {
  if (!is_time_metric(column.metric)) return "";
  const std::string stem = column.metric.substr(0, column.metric.size() - 3) + ".";
  std::set<std::string> passes;
  size_t depth = 0;
  for (const auto& [index, rows] : items)
    for (const Row* r : rows)
      if (r->metric.rfind(stem, 0) == 0 && is_time_metric(r->metric) &&
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
    const SelectionMean a = selection_mean(lower, c, items);
    const SelectionMean b = selection_mean(than, c, items);
    const double d = a.mean - b.mean;
    sum += d;
    if (largest.empty() || std::abs(d) > std::abs(largest_diff)) largest = p, largest_diff = d;
  }
  std::string out =
      "; largest pass difference " + largest + " " + signed_text(largest_diff, 3) + " ms";
  const double outside = difference - sum;
  if (std::abs(outside) > std::abs(largest_diff))
    out += "; " + signed_text(outside, 3) +
           " ms lies outside the timed passes (allocation, host work, synchronisation)";
  return out;
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
      s.indices.push_back(index);
    }
  }
  if (s.items) s.mean = sum / s.items;
  return s;
}

namespace {

// An item's first row, or nullptr.
const Row* first_row(const std::map<int, std::vector<const Row*>>& items, int index) {
  const auto it = items.find(index);
  return it == items.end() || it->second.empty() ? nullptr : it->second.front();
}

// The items of the first run matching `selector` that have `column`.
std::vector<int> matching_items(const std::string& selector, const Column& column,
                                const RunView& run) {
  std::vector<int> out;
  for (const auto& [index, rows] : run.items)
    if (!rows.empty() && selector_matches(selector, *rows.front()) && find_row(rows, column))
      out.push_back(index);
  return out;
}

bool is_error_column(const Column& c) {
  return c.metric.rfind("probe_error_", 0) == 0 &&
         (c.stat == "mean" || c.stat == "max" || c.stat == "p99");
}

// "item 4: stats.storage.overflowed_texels = 8816, stats.storage.overflow_max_error = 1; 3 of 8
// items lossy": the items with a loss (lossy.h) in any run, the first such item's rows named;
// empty when no item has one.
std::string lossy_rows(const std::vector<int>& items, const std::vector<RunView>& runs) {
  std::string first;
  int lossy = 0;
  for (int index : items) {
    std::vector<const Row*> rows;  // the item's rows of every run, first run first
    for (const RunView& run : runs)
      if (const auto it = run.items.find(index); it != run.items.end())
        rows.insert(rows.end(), it->second.begin(), it->second.end());
    const std::string named = loss_text(rows);
    if (named.empty()) continue;
    if (first.empty()) first = "item " + std::to_string(index) + ": " + named;
    ++lossy;
  }
  if (first.empty()) return "";
  return first + "; " + std::to_string(lossy) + " of " + std::to_string(items.size()) +
         " items lossy";
}

// The signed errors of a probe class in an item's samples; "all": the classes the samples'
// "probe_all" names (those probe_error_all pools), else every class, in name order.
std::vector<double> class_errors(const nlohmann::json& samples, const std::string& name) {
  std::vector<double> out;
  if (!samples.contains("probe_errors")) return out;
  const nlohmann::json pooled = samples.value("probe_all", nlohmann::json::array());
  for (const auto& [c, errors] : samples["probe_errors"].items())
    if (c == name || (name == "all" && (pooled.empty() || std::find(pooled.begin(), pooled.end(),
                                                                    c) != pooled.end())))
      for (const auto& e : errors) out.push_back(e.get<double>());
  return out;
}

const nlohmann::json* samples_of(const RunView& run, int index) {
  const auto it = run.samples.find(index);
  return it == run.samples.end() || it->second.is_null() ? nullptr : &it->second;
}

// Whether a column is a repeated timing: its rows are a median/min/max, or samples time it.
bool is_timing_column(const Column& c, const std::vector<int>& items,
                      const std::vector<RunView>& runs) {
  for (int index : items) {
    const auto it = runs[0].items.find(index);
    if (const Row* r = find_row(it->second, c);
        r && (r->stat == "median" || r->stat == "min" || r->stat == "max"))
      return true;
    for (const RunView& run : runs)
      if (const nlohmann::json* s = samples_of(run, index);
          s && s->contains("timings") && (*s)["timings"].contains(c.metric))
        return true;
  }
  return false;
}

// Per item, per run: the repetitions (a timing) or the row's value, empty for a run without
// them (so runs keep their places); an item without any is reported through `missing`.
// `measured_runs`: the most runs any item has data in.
std::vector<RunSamples> run_samples(const std::vector<int>& items, const Column& column,
                                    bool timing, const std::vector<RunView>& runs, int& missing,
                                    size_t& measured_runs, size_t& repetitions) {
  std::vector<RunSamples> out;
  for (int index : items) {
    RunSamples item;
    size_t measured = 0;
    for (const RunView& run : runs) {
      std::vector<double> samples;
      if (timing) {
        if (const nlohmann::json* s = samples_of(run, index);
            s && s->contains("timings") && (*s)["timings"].contains(column.metric))
          for (const auto& v : (*s)["timings"][column.metric]) samples.push_back(v.get<double>());
      } else if (const auto it = run.items.find(index); it != run.items.end()) {
        if (const Row* r = find_row(it->second, column)) samples.push_back(r->value);
      }
      repetitions = std::max(repetitions, samples.size());
      measured += !samples.empty();
      item.push_back(std::move(samples));
    }
    if (!measured) {
      ++missing;
      continue;
    }
    measured_runs = std::max(measured_runs, measured);
    out.push_back(std::move(item));
  }
  return out;
}

Comparison not_comparable(Comparison c, const std::string& why) {
  c.verdict = "not comparable (" + why + ")";
  return c;
}

// A difference's interval gets the wider practical band of its two columns (none for ratios,
// whose band of no effect is kSmallestRatio or the A/A tie band); the basis names it.
void apply_practical_band(Comparison& c, const PracticalBands& bands, const Column& first,
                          const Column& second, const std::string& unit) {
  if (c.interval.ratio) return;
  c.interval.difference_band =
      std::max(practical_band(bands, first), practical_band(bands, second));
  if (c.interval.difference_band > 0.0)
    c.basis += "; practical band ±" + significant_text(c.interval.difference_band, 3) +
               (unit.empty() || unit == "1" ? "" : " " + unit) + " (suite)";
}

std::string verdict_of(const EffectInterval& iv) {
  return iv.below() ? "confirmed" : iv.above() ? "refuted" : "tie";
}

// The verdict of a comparison with an interval: none where both sides measure 0 (a count that
// stays 0, errors exact on both sides), which says nothing about the claim, else verdict_of.
void decide(Comparison& c) {
  if (c.first == 0.0 && c.second == 0.0) {
    c.has_interval = false;
    c.verdict = "not comparable (0 against 0: both sides measure 0)";
    return;
  }
  c.has_interval = true;
  c.verdict = verdict_of(c.interval);
}

std::string level_text(const nlohmann::json& v) {
  return v.is_string() ? v.get<std::string>() : v.dump();
}

// The levels of a trend: the given ones, else the distinct values of `over` among the matching
// items (numbers ascending when every value is one; else in item order).
std::vector<std::string> trend_levels(const nlohmann::json& f, const Column& column,
                                      const RunView& run) {
  std::vector<std::string> levels;
  if (f.contains("levels")) {
    for (const auto& v : f["levels"]) levels.push_back(level_text(v));
    return levels;
  }
  const std::string over = f["over"].get<std::string>();
  for (int index : matching_items(f["selector"].get<std::string>(), column, run)) {
    const Row& r = *run.items.at(index).front();
    std::string value;
    if (over == "scene") {
      value = r.scene;
    } else {
      for (const std::string& w : words(r.params))
        if (w.rfind(over + "=", 0) == 0) value = w.substr(over.size() + 1);
    }
    if (!value.empty() && std::find(levels.begin(), levels.end(), value) == levels.end())
      levels.push_back(value);
  }
  bool numeric = true;
  for (const std::string& l : levels) {
    char* end = nullptr;
    std::strtod(l.c_str(), &end);
    numeric &= end && *end == '\0';
  }
  if (numeric)
    std::sort(levels.begin(), levels.end(), [](const std::string& a, const std::string& b) {
      return std::strtod(a.c_str(), nullptr) < std::strtod(b.c_str(), nullptr);
    });
  return levels;
}

// The suite's reading after the data: `why` for a confirmed claim, else `why_not`.
// Whether a finding says its claim is about a loss ("lossy": "expected", suite-format.md).
bool expects_loss(const nlohmann::json& f) {
  return f.value("lossy", "") == "expected";
}

std::string reading(const nlohmann::json& f, bool confirmed) {
  const std::string text = confirmed ? f.value("why", "") : f.value("why_not", "");
  if (text.empty()) return confirmed ? "" : "; the cause is not explained here";
  return "; " + std::string(confirmed ? "reading: " : "") + text;
}

FindingResult evaluate_trend(const nlohmann::json& f, const std::vector<RunView>& runs,
                             const TieBands& tie_bands, const PracticalBands& practical_bands) {
  FindingResult r;
  r.claim = f["claim"].get<std::string>();
  r.why = f.value("why", "");
  const std::string selector = f["selector"].get<std::string>();
  const std::string over = f["over"].get<std::string>();
  const std::string trend = f["trend"].get<std::string>();
  const Column column = parse_column(f["column"].get<std::string>());
  r.lower_text =
      selector + ": " + f["column"].get<std::string>() + " over " + over + " (" + trend + ")";
  const std::vector<std::string> levels = trend_levels(f, column, runs[0]);
  if (levels.size() < 2) {
    r.verdict = "not comparable (fewer than two levels of " + over + " among the items)";
    return r;
  }
  size_t from = 1;
  if (trend == "plateau" && f.contains("from")) {
    const auto it = std::find(levels.begin(), levels.end(), level_text(f["from"]));
    if (it == levels.end()) {
      r.verdict = "not comparable (the plateau's level " + level_text(f["from"]) +
                  " is not among the levels of " + over + ")";
      return r;
    }
    from = size_t(it - levels.begin());
  }
  const uint64_t seed = seed_of(r.claim + r.lower_text);
  std::string problem;
  int along = 0, against = 0, tested = 0;
  for (size_t k = 0; k + 1 < levels.size(); ++k) {
    const std::string here = selector + " " + over + "=" + levels[k];
    const std::string next = selector + " " + over + "=" + levels[k + 1];
    TrendStep step{levels[k], levels[k + 1],
                   compare_selections(next, column, here, column, runs, seed + k, false,
                                      expects_loss(f), tie_bands, practical_bands)};
    const Comparison& c = step.comparison;
    r.effect += (r.effect.empty() ? "" : "; ") + levels[k] + " → " + levels[k + 1] + ": " +
                (c.has_interval ? interval_text(c.interval) : c.verdict);
    if (r.basis.empty()) r.basis = c.basis;
    if (!c.has_interval) {
      if (problem.empty() || c.verdict.rfind("defect", 0) == 0)
        problem = c.verdict.substr(0, c.verdict.find(" (")) + " (step " + levels[k] + " → " +
                  levels[k + 1] + ": " + c.verdict + ")";
    } else if (trend == "plateau") {
      if (k >= from) {
        ++tested;
        along += !c.interval.below() && !c.interval.above();
        against += c.interval.below() || c.interval.above();
      }
    } else {
      ++tested;
      const bool up = trend == "increasing";
      along += up ? c.interval.above() : c.interval.below();
      against += up ? c.interval.below() : c.interval.above();
    }
    r.steps.push_back(std::move(step));
  }
  if (!problem.empty())
    r.verdict = problem;
  else if (tested == 0)
    r.verdict = "not comparable (no step from level " + levels[from] + " on)";
  else if (against)
    r.verdict = "refuted";
  else  // a plateau whose every step holds "no effect" is a tie, as the claim says, never more
    r.verdict = along == tested && trend != "plateau" ? "confirmed" : "tie";
  r.explanation = std::to_string(along) + " of " + std::to_string(tested) + " tested steps " +
                  (trend == "plateau" ? "flat (from " + over + "=" + levels[from] + ")"
                                      : "in the claimed direction") +
                  (against ? ", " + std::to_string(against) + " against it" : "") +
                  reading(f, problem.empty() && tested > 0 && along == tested);
  return r;
}

}  // namespace

std::string interval_text(const EffectInterval& iv) {
  if (iv.ratio)
    return significant_text(iv.effect, 3) + "x [" + significant_text(iv.low, 3) + ", " +
           significant_text(iv.high, 3) + "]";
  return signed_text(iv.effect, 3) + " [" + signed_text(iv.low, 3) + ", " +
         signed_text(iv.high, 3) + "]";
}

Comparison compare_selections(const std::string& first_selector, const Column& first_column,
                              const std::string& second_selector, const Column& second_column,
                              const std::vector<RunView>& runs, uint64_t seed, bool difference,
                              bool lossy_expected, const TieBands& tie_bands,
                              const PracticalBands& practical_bands) {
  Comparison c;
  const RunView& run = runs[0];
  const SelectionMean a = selection_mean(first_selector, first_column, run.items);
  const SelectionMean b = selection_mean(second_selector, second_column, run.items);
  c.first = a.mean;
  c.second = b.mean;
  c.first_items = a.items;
  c.second_items = b.items;
  if (!a.items || !b.items)
    return not_comparable(
        c, "no measured item matches the " + std::string(!a.items ? "first" : "second") + " side");
  const std::vector<int> first = matching_items(first_selector, first_column, run);
  const std::vector<int> second = matching_items(second_selector, second_column, run);
  std::vector<int> both = first;
  both.insert(both.end(), second.begin(), second.end());
  const std::string lossy = lossy_rows(both, runs);
  if (!lossy.empty() && !lossy_expected) {
    c.verdict = "defect (" + lossy + ": the measurement lost data)";
    return c;
  }
  const std::string unit_a = find_row(run.items.at(first.front()), first_column)->unit;
  const std::string unit_b = find_row(run.items.at(second.front()), second_column)->unit;
  if (unit_a != unit_b) return not_comparable(c, "units differ: " + unit_a + " vs " + unit_b);
  const std::string items_text =
      std::to_string(first.size()) + " vs " + std::to_string(second.size()) + " items";
  if (is_error_column(first_column) || is_error_column(second_column)) {
    if (first_column.stat != second_column.stat || !is_error_column(first_column) ||
        !is_error_column(second_column))
      return not_comparable(c, "probe errors against another statistic");
    std::vector<std::vector<double>> errors;
    errors.reserve(both.size());
    std::vector<PointErrors> sides[2];
    for (size_t i = 0; i < both.size(); ++i) {
      const int index = both[i];
      const nlohmann::json* s = samples_of(run, index);
      const Column& column = i < first.size() ? first_column : second_column;
      errors.push_back(s ? class_errors(*s, column.metric.substr(12)) : std::vector<double>{});
      if (!s || !s->contains("probe_errors"))
        return not_comparable(c, "no probe samples for item " + std::to_string(index) +
                                     ": interval unavailable (a result folder from before "
                                     "samples/, or its probe errors left out)");
    }
    for (size_t i = 0; i < both.size(); ++i)
      sides[i < first.size() ? 0 : 1].push_back({&errors[i], first_row(run.items, both[i])->scene});
    c.interval = paired_bootstrap(sides[0], sides[1], first_column.stat, seed);
    c.basis = std::to_string(errors.front().size()) +
              " probe errors per item (paired over the points of each scene, first run), " +
              items_text;
    if (!lossy.empty()) c.basis += "; lossy as the claim expects (" + lossy + ")";
    apply_practical_band(c, practical_bands, first_column, second_column, unit_a);
    decide(c);
    return c;
  }
  const bool timing =
      is_timing_column(first_column, first, runs) || is_timing_column(second_column, second, runs);
  int missing = 0;
  size_t measured_runs = 0, repetitions = 0;
  const std::vector<RunSamples> sa =
      run_samples(first, first_column, timing, runs, missing, measured_runs, repetitions);
  const std::vector<RunSamples> sb =
      run_samples(second, second_column, timing, runs, missing, measured_runs, repetitions);
  if (missing)
    return not_comparable(c, std::to_string(missing) +
                                 " items without per-repetition samples: interval unavailable "
                                 "(a result folder from before samples/)");
  c.first = side_mean(sa);
  c.second = side_mean(sb);
  const RunInterval ri = run_interval(sa, sb, difference);
  const std::string runs_text = std::to_string(ri.runs) + " run" + (ri.runs == 1 ? "" : "s");
  c.basis = runs_text + " x " +
            (timing ? std::to_string(repetitions) + " repetitions" : "1 value") + ", " + items_text;
  if (ri.runs < measured_runs)
    c.basis += " (" + std::to_string(measured_runs - ri.runs) +
               " more left out: an item of a side was not measured in them)";
  if (!lossy.empty()) c.basis += "; lossy as the claim expects (" + lossy + ")";
  if (ri.runs < 2)
    return not_comparable(c, runs_text +
                                 ": a t-interval over runs needs at least 2; run the "
                                 "suite with --runs 5");
  c.interval = ri.interval;
  if (c.interval.ratio)
    for (const Column* column : {&first_column, &second_column})
      if (const auto it = tie_bands.find(column->metric);
          it != tie_bands.end() && it->second > c.interval.band)
        c.interval.band = it->second;
  if (c.interval.ratio && c.interval.band > kSmallestRatio)
    c.basis += "; tie band ±" + significant_text(100.0 * c.interval.band, 2) + " % (A/A)";
  apply_practical_band(c, practical_bands, first_column, second_column, unit_a);
  decide(c);
  return c;
}

double practical_band(const PracticalBands& bands, const Column& column) {
  if (const auto it = bands.find(column.metric + ":" + column.stat);
      !column.stat.empty() && it != bands.end())
    return it->second;
  const auto it = bands.find(column.metric);
  return it == bands.end() ? 0.0 : it->second;
}

namespace {

// Whether any item of the run has a row of `metric`.
bool carries(const RunView& run, const std::string& metric) {
  for (const auto& [index, rows] : run.items)
    for (const Row* r : rows)
      if (r->metric == metric) return true;
  return false;
}

FindingResult evaluate_comparison(const nlohmann::json& f, const std::vector<RunView>& runs,
                                  const TieBands& tie_bands,
                                  const PracticalBands& practical_bands) {
  FindingResult r;
  r.claim = f["claim"].get<std::string>();
  r.why = f.value("why", "");
  const std::string lower_selector = f["lower"][0].get<std::string>();
  const std::string than_selector = f["than"][0].get<std::string>();
  r.lower_text = lower_selector + ": " + f["lower"][1].get<std::string>();
  r.than_text = than_selector + ": " + f["than"][1].get<std::string>();
  const Column lower_column = parse_column(f["lower"][1].get<std::string>());
  const Column than_column = parse_column(f["than"][1].get<std::string>());
  const Comparison c = compare_selections(lower_selector, lower_column, than_selector, than_column,
                                          runs, seed_of(r.claim + r.lower_text), false,
                                          expects_loss(f), tie_bands, practical_bands);
  r.lower = c.first;
  r.than = c.second;
  r.lower_items = c.first_items;
  r.than_items = c.second_items;
  r.verdict = c.verdict;
  r.basis = c.basis;
  r.effect = c.has_interval ? interval_text(c.interval) : "-";
  if (!c.first_items || !c.second_items) {
    r.explanation = "-";
    return r;
  }
  const double difference = c.first - c.second;
  r.explanation = difference == 0.0
                      ? "both sides equal"
                      : "first side " + std::string(difference < 0.0 ? "lower" : "higher") +
                            " by " + significant_text(std::abs(difference), 3);
  if (c.second != 0.0) r.explanation += " (" + significant_text(c.first / c.second, 3) + "x)";
  if (f["lower"][1] == f["than"][1]) {
    // The passes are read from the first run's rows: so is the total they split.
    const double rows_difference =
        selection_mean(lower_selector, lower_column, runs[0].items).mean -
        selection_mean(than_selector, than_column, runs[0].items).mean;
    r.explanation +=
        pass_breakdown(lower_selector, than_selector, lower_column, rows_difference, runs[0].items);
  }
  r.explanation += reading(f, r.verdict == "confirmed");
  return r;
}

}  // namespace

std::vector<FindingResult> evaluate_findings(const nlohmann::json& findings,
                                             const std::vector<RunView>& runs,
                                             const TieBands& tie_bands,
                                             const PracticalBands& practical_bands) {
  std::vector<FindingResult> out;
  if (!findings.is_array() || runs.empty()) return out;
  for (const auto& f : findings) {
    FindingResult r = f.contains("trend")
                          ? evaluate_trend(f, runs, tie_bands, practical_bands)
                          : evaluate_comparison(f, runs, tie_bands, practical_bands);
    r.timer = f.value("timer", "");
    if (!r.timer.empty() && r.timer != "none" && !carries(runs[0], r.timer))
      r.verdict = "not comparable (no row carries the timer " + r.timer + ")";
    if (const std::string reason = f.value("not_as_paper", ""); !reason.empty())
      r.verdict = "cannot be tested as the paper did: " + reason + " (ours: " + r.verdict + ")";
    out.push_back(std::move(r));
  }
  return out;
}

}  // namespace dv
