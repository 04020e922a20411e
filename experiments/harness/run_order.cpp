// Item order of a replicate-protocol run (run_order.h).
#include "experiments/harness/run_order.h"

#include <map>
#include <random>
#include <set>
#include <utility>

#include "experiments/harness/findings.h"
#include "experiments/harness/rows.h"

namespace dv {

namespace {

// An item as the findings' selectors see its rows.
Row row_of(const RunItem& item) {
  Row r;
  r.experiment = item.experiment_name;
  r.scene = item.scene;
  r.strategy = item.strategy;
  r.params = item.params_text();
  return r;
}

}  // namespace

std::vector<RunItem> protocol_order(const std::vector<RunItem>& items, const Suite& suite,
                                    uint64_t seed) {
  std::vector<RunItem> shuffled = items;
  std::mt19937_64 rng(seed);
  for (size_t i = shuffled.size(); i > 1; --i) std::swap(shuffled[i - 1], shuffled[rng() % i]);
  // Pairs of positions in `shuffled`: a comparison's first side with its second.
  std::map<size_t, size_t> partner;
  std::set<size_t> first_side;
  for (const ExperimentSpec& e : suite.experiments) {
    if (!e.findings.is_array()) continue;
    for (const auto& f : e.findings) {
      if (!f.contains("lower") || !f.contains("than")) continue;
      std::vector<size_t> sides[2];
      for (size_t i = 0; i < shuffled.size(); ++i) {
        if (shuffled[i].experiment_name != e.name || partner.count(i)) continue;
        const Row r = row_of(shuffled[i]);
        if (selector_matches(f["lower"][0].get<std::string>(), r))
          sides[0].push_back(i);
        else if (selector_matches(f["than"][0].get<std::string>(), r))
          sides[1].push_back(i);
      }
      for (size_t k = 0; k < sides[0].size() && k < sides[1].size(); ++k) {
        partner[sides[0][k]] = sides[1][k];
        partner[sides[1][k]] = sides[0][k];
        first_side.insert(sides[0][k]);
      }
    }
  }
  // Walk the permuted order; a paired item brings its partner, first side first in every other
  // pair.
  std::vector<RunItem> out;
  std::set<size_t> placed;
  bool first_side_first = (seed & 1) == 0;
  for (size_t i = 0; i < shuffled.size(); ++i) {
    if (placed.count(i)) continue;
    const auto it = partner.find(i);
    if (it == partner.end()) {
      out.push_back(shuffled[i]);
      placed.insert(i);
      continue;
    }
    const size_t a = first_side.count(i) ? i : it->second, b = a == i ? it->second : i;
    out.push_back(shuffled[first_side_first ? a : b]);
    out.push_back(shuffled[first_side_first ? b : a]);
    placed.insert(a);
    placed.insert(b);
    first_side_first = !first_side_first;
  }
  return out;
}

}  // namespace dv
