// Findings evaluated against an experiment's rows (findings.h).
#include "experiments/harness/findings.h"

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

struct Side {
  double mean = 0.0;
  int items = 0;
};

Side side_mean(const nlohmann::json& side, const std::map<int, std::vector<const Row*>>& items) {
  const std::string selector = side[0].get<std::string>();
  const Column column = parse_column(side[1].get<std::string>());
  Side s;
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

}  // namespace

bool selector_matches(const std::string& selector, const Row& r) {
  for (const std::string& term : words(selector))
    if (!term_matches(term, r)) return false;
  return true;
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
    const Side lower = side_mean(f["lower"], items), than = side_mean(f["than"], items);
    r.lower = lower.mean;
    r.than = than.mean;
    r.lower_items = lower.items;
    r.than_items = than.items;
    if (!lower.items || !than.items)
      r.verdict = "undecided (no measured item matches " +
                  std::string(!lower.items ? "the first" : "the second") + " side)";
    else
      r.verdict = lower.mean < than.mean ? "confirmed" : "not confirmed";
    out.push_back(std::move(r));
  }
  return out;
}

}  // namespace dv
