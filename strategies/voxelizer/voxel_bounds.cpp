// Voxel grid resolutions and bounds from text and meshes (see voxel_bounds.h).
#include "strategies/voxelizer/voxel_bounds.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <vector>

#include "core/error.h"
#include "strategies/voxelizer/voxel_grid.h"

namespace dv {

namespace {

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  size_t start = 0;
  for (;;) {
    const size_t end = text.find(separator, start);
    parts.push_back(text.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) return parts;
    start = end + 1;
  }
}

}  // namespace

ivec3 parse_voxel_resolution(const std::string& text, const std::string& where) {
  std::vector<std::string> parts = split(text, 'x');
  if (parts.size() == 1) parts = {parts[0], parts[0], parts[0]};
  if (parts.size() != 3)
    throw InputError(where, "expected WxHxD (e.g. 512x512x32), got '" + text + "'");
  ivec3 res;
  for (int a = 0; a < 3; ++a) {
    const std::string& p = parts[size_t(a)];
    if (p.empty() || p.size() > 9 ||
        !std::all_of(p.begin(), p.end(), [](char c) { return c >= '0' && c <= '9'; }))
      throw InputError(where, "expected WxHxD with positive whole numbers, got '" + text + "'");
    res[a] = std::atoi(p.c_str());
  }
  GridSpec probe;
  probe.res = res;
  probe.bounds = {dvec3(0.0), dvec3(1.0)};
  validate_grid_spec(probe, where);
  return res;
}

Aabb parse_voxel_bounds(const std::string& text, const std::string& where) {
  const std::vector<std::string> parts = split(text, ',');
  if (parts.size() != 6)
    throw InputError(where, "expected six numbers x0,y0,z0,x1,y1,z1, got '" + text + "'");
  double v[6];
  for (int i = 0; i < 6; ++i) {
    const std::string& p = parts[size_t(i)];
    char* end = nullptr;
    v[i] = std::strtod(p.c_str(), &end);
    if (p.empty() || end != p.c_str() + p.size() || !std::isfinite(v[i]))
      throw InputError(where, "'" + p + "' is not a finite number");
  }
  const Aabb box{dvec3(v[0], v[1], v[2]), dvec3(v[3], v[4], v[5])};
  for (int a = 0; a < 3; ++a)
    if (!(box.hi[a] > box.lo[a]))
      throw InputError(where, "the upper corner must exceed the lower one on every axis");
  return box;
}

Aabb cubic_bounds(const Aabb& box, const std::string& where) {
  if (box.empty()) throw InputError(where, "nothing to voxelize (no triangles)");
  const dvec3 e = box.extent();
  const double side = std::max({e.x, e.y, e.z});
  if (!(side > 0.0)) throw InputError(where, "the triangles span no volume; give --bounds");
  const dvec3 c = box.center();
  return {c - 0.5 * side, c + 0.5 * side};
}

}  // namespace dv
