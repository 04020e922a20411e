// Point lists for `deepvox probe`: read x,y,z rows (an optional header line), write one row of
// per-light transmittances per point, in input order.
#pragma once

#include <string>
#include <vector>

#include "core/math.h"

namespace dv {

std::vector<dvec3> read_points_csv(const std::string& path);

// values[i * light_count + l] is the transmittance of light l at point i.
void write_transmittance_csv(const std::string& path, const std::vector<dvec3>& points,
                             const std::vector<double>& values, int light_count);

}  // namespace dv
