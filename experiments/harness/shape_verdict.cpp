// Shape rows' verdicts and a table's sentence (shape_verdict.h).
#include "experiments/harness/shape_verdict.h"

#include <algorithm>
#include <cmath>

#include "core/number_text.h"

namespace dv {

namespace {

ShapeVerdict not_comparable(const std::string& why) {
  return {ShapeVerdict::Kind::not_comparable, "not comparable (" + why + ")"};
}

// "0.52–0.98 ms" over the rows' sides; empty when none is a time.
std::string load_range(const std::vector<const ShapeRow*>& rows) {
  double low = INFINITY, high = -INFINITY;
  for (const ShapeRow* r : rows)
    if (r->time)
      for (double v : {r->first, r->second}) low = std::min(low, v), high = std::max(high, v);
  if (low > high) return "";
  return significant_text(low, 3) + "–" + significant_text(high, 3) + " ms";
}

std::string names(const std::vector<const ShapeRow*>& rows, bool with_verdict) {
  std::string out;
  for (const ShapeRow* r : rows) {
    out += (out.empty() ? "" : "; ") + r->what;
    if (with_verdict) {
      // "differs (ours 0.45x the paper's)" -> "(ours 0.45x the paper's)"
      const size_t open = r->verdict.text.find(" (");
      if (open != std::string::npos) out += r->verdict.text.substr(open);
    }
  }
  return out;
}

}  // namespace

ShapeVerdict shape_verdict(double paper_first, double paper_second, const Comparison& ours,
                           bool difference, double band) {
  if (std::isnan(paper_first) || std::isnan(paper_second))
    return not_comparable("the paper prints no number on a side");
  if (!difference && paper_first == 0.0 && paper_second == 0.0)
    return not_comparable("0 against 0 in the paper");
  if (!difference && paper_second == 0.0) return not_comparable("the paper's ratio divides by 0");
  if (ours.first_items && ours.second_items && ours.first == 0.0 && ours.second == 0.0)
    return not_comparable("0 against 0 in ours");
  if (!ours.has_interval) {
    // "not comparable (why)" -> "ours: why"; a defect keeps its word.
    const std::string prefix = "not comparable (";
    const bool nested = ours.verdict.rfind(prefix, 0) == 0 && ours.verdict.back() == ')';
    return not_comparable(
        "ours: " +
        (nested ? ours.verdict.substr(prefix.size(), ours.verdict.size() - prefix.size() - 1)
                : ours.verdict));
  }
  const EffectInterval& iv = ours.interval;
  if (iv.ratio == difference)
    return not_comparable(difference ? "ours is a ratio, the paper's a difference"
                                     : "ours is a difference: a side is 0 in some run");
  const double paper = difference ? paper_first - paper_second : paper_first / paper_second;
  if (paper >= iv.low && paper <= iv.high)
    return {ShapeVerdict::Kind::inside, "reproduces (inside our interval)"};
  const double low = difference ? iv.low - band * std::abs(iv.low) : iv.low / (1.0 + band);
  const double high = difference ? iv.high + band * std::abs(iv.high) : iv.high * (1.0 + band);
  const std::string within = "within ±" + significant_text(100.0 * band, 2) + " %";
  if (paper >= low && paper <= high)
    return {ShapeVerdict::Kind::within_band, "reproduces (" + within + ")"};
  if (difference)
    return {ShapeVerdict::Kind::differs,
            "differs (ours " + std::string(iv.effect < paper ? "lower" : "higher") + " by " +
                significant_text(std::abs(iv.effect - paper), 3) + ")"};
  return {ShapeVerdict::Kind::differs,
          "differs (ours " + significant_text(iv.effect / paper, 3) + "x the paper's)"};
}

std::string shape_sentence(const std::vector<ShapeRow>& rows, double band) {
  std::vector<const ShapeRow*> reproduce, differ, other;
  int inside = 0;
  for (const ShapeRow& r : rows) {
    if (r.verdict.reproduces())
      reproduce.push_back(&r);
    else if (r.verdict.kind == ShapeVerdict::Kind::differs)
      differ.push_back(&r);
    else
      other.push_back(&r);
    inside += r.verdict.kind == ShapeVerdict::Kind::inside;
  }
  std::string s = std::to_string(reproduce.size()) + " of " + std::to_string(rows.size()) +
                  " rows reproduce the paper (" + std::to_string(inside) +
                  " inside our 95 % interval, " +
                  std::to_string(reproduce.size() - size_t(inside)) + " within ±" +
                  significant_text(100.0 * band, 2) + " %)";
  if (!reproduce.empty()) s += ": " + names(reproduce, false);
  s += "; " + std::to_string(differ.size()) + " differ" + (differ.size() == 1 ? "s" : "");
  if (!differ.empty()) s += ": " + names(differ, true);
  if (!other.empty())
    s += "; " + std::to_string(other.size()) + " not comparable (" + names(other, false) + ")";
  const std::string at_reproduce = load_range(reproduce), at_differ = load_range(differ);
  if (!at_reproduce.empty() || !at_differ.empty()) {
    s += ". Our loads: ";
    if (!at_reproduce.empty()) s += at_reproduce + " where the rows reproduce";
    if (!at_reproduce.empty() && !at_differ.empty()) s += ", ";
    if (!at_differ.empty()) s += at_differ + " where they differ";
  }
  return s + ".";
}

}  // namespace dv
