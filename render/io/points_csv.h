// Point lists for `deepvox probe`: read x,y,z rows (an optional header line), write one row of
// per-light transmittances (luminance, then per colour channel) per point, in input order.
#pragma once

#include <string>
#include <vector>

#include "core/math.h"

namespace dv {

std::vector<dvec3> read_points_csv(const std::string& path);

// values[i * light_count + l] is the (luminance) transmittance of light l at point i, rgb[...]
// the same per colour channel. Columns: x,y,z, light0..lightN-1 (luminance, where scripts have
// always found them), then light0_r,light0_g,light0_b, ... per light.
void write_transmittance_csv(const std::string& path, const std::vector<dvec3>& points,
                             const std::vector<double>& values, const std::vector<dvec3>& rgb,
                             int light_count);

}  // namespace dv
