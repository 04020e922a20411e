// Pareto fronts and their regime sentences (pareto.h).
#include "experiments/harness/pareto.h"

#include <algorithm>
#include <cmath>

#include "core/number_text.h"

namespace dv {

std::vector<size_t> pareto_front(const std::vector<ParetoPoint>& points) {
  std::vector<size_t> order;
  for (size_t i = 0; i < points.size(); ++i)
    if (std::isfinite(points[i].cost) && std::isfinite(points[i].error)) order.push_back(i);
  // Cost ascending, then error ascending, then input order: a sweep keeps a point only when
  // its error is below every cheaper (or equally cheap) point's.
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    if (points[a].cost != points[b].cost) return points[a].cost < points[b].cost;
    return points[a].error < points[b].error;
  });
  std::vector<size_t> front;
  for (size_t i : order)
    if (front.empty() || points[i].error < points[front.back()].error) front.push_back(i);
  return front;
}

std::string pareto_regimes(const std::vector<ParetoPoint>& points, const std::vector<size_t>& front,
                           const std::string& cost_name, const std::string& error_name) {
  if (front.empty()) return "No point has both " + cost_name + " and " + error_name + ".";
  const ParetoPoint& cheapest = points[front.front()];
  const ParetoPoint& best = points[front.back()];
  if (front.size() == 1)
    return cheapest.label + " wins every regime: cheapest (" + cost_name + " " +
           significant_text(cheapest.cost, 4) + ") and most accurate (" + error_name + " " +
           significant_text(cheapest.error, 4) + ").";
  std::string s = "Cheapest: " + cheapest.label + " (" + cost_name + " " +
                  significant_text(cheapest.cost, 4) + ", " + error_name + " " +
                  significant_text(cheapest.error, 4) + ")";
  for (size_t k = 1; k + 1 < front.size(); ++k) {
    const ParetoPoint& p = points[front[k]];
    s += "; from " + cost_name + " " + significant_text(p.cost, 4) + ": " + p.label + " (" +
         error_name + " " + significant_text(p.error, 4) + ")";
  }
  s += "; most accurate: " + best.label + " (" + error_name + " " +
       significant_text(best.error, 4) + " from " + cost_name + " " +
       significant_text(best.cost, 4) + ").";
  return s;
}

}  // namespace dv
