// Pareto fronts of (error, cost) points, both smaller-is-better: the accuracy suite's answer to
// "what does accuracy cost". The report prints one front per scene and cost (time, bytes) and
// names the winner per regime from it.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace dv {

struct ParetoPoint {
  double cost = 0.0;   // x: time or bytes
  double error = 0.0;  // y: |T' - T| or an image error
  std::string label;   // who (strategy and parameters)
};

// Indices of the non-dominated points (no other point is <= in both and < in one), sorted by
// cost ascending (so error descending); of identical points the first is kept. Points with a
// non-finite coordinate are never on the front.
std::vector<size_t> pareto_front(const std::vector<ParetoPoint>& points);

// One generated sentence naming the winner per regime along a front (indices from
// pareto_front): the cheapest point, the most accurate one, and those in between with the
// cost range in which each is the most accurate choice.
std::string pareto_regimes(const std::vector<ParetoPoint>& points, const std::vector<size_t>& front,
                           const std::string& cost_name, const std::string& error_name);

}  // namespace dv
