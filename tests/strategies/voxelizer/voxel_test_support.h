// Helpers of the voxel tests: grids whose world coordinates are grid coordinates, brute-force
// voxel sets (every voxel of the grid tested, no work split or pruning), and grid comparisons.
#pragma once

#include <gtest/gtest.h>

#include <set>
#include <tuple>
#include <vector>

#include "strategies/voxelizer/exact_voxelizer.h"
#include "strategies/voxelizer/sat_device.h"
#include "strategies/voxelizer/voxel_grid.h"

namespace dv::test {

using Voxel = std::tuple<int, int, int>;
using VoxelSet = std::set<Voxel>;

// A grid of res voxels of unit size with its lower corner at the origin.
inline GridSpec unit_grid(ivec3 res) {
  return make_box_grid(res, Aabb{dvec3(0.0), dvec3(res)});
}

inline VoxelSet voxels_of(const VoxelGrid& grid) {
  const VoxelGrid host = grid.copy_to(Memory::host);
  VoxelSet out;
  const ivec3 r = host.spec().res;
  for (int z = 0; z < r.z; ++z)
    for (int y = 0; y < r.y; ++y)
      for (int x = 0; x < r.x; ++x)
        if (host.get(x, y, z)) out.insert({x, y, z});
  return out;
}

// Every voxel tested with the 13-axis separating-axis test (grid coordinates = world).
inline VoxelSet brute_force_exact(const std::vector<dvec3>& corners, ivec3 res, double half = 0.5) {
  VoxelSet out;
  for (size_t t = 0; t + 2 < corners.size(); t += 3) {
    const dvec3 &a = corners[t], &b = corners[t + 1], &c = corners[t + 2];
    const dvec3 n = triangle_normal(a, b, c);
    const bool use_normal = !is_degenerate_triangle(a, b, c, n);
    for (int z = 0; z < res.z; ++z)
      for (int y = 0; y < res.y; ++y)
        for (int x = 0; x < res.x; ++x)
          if (triangle_box_overlap(a, b, c, n, use_normal, dvec3(x, y, z) + 0.5, dvec3(half)))
            out.insert({x, y, z});
  }
  return out;
}

// Every voxel of the triangle's bounding range tested with sat's own per-voxel decision.
inline VoxelSet brute_force_sat(const std::vector<dvec3>& corners, ivec3 res) {
  VoxelSet out;
  for (size_t t = 0; t + 2 < corners.size(); t += 3) {
    SatTriangle tri;
    if (!sat_setup(corners[t], corners[t + 1], corners[t + 2], res, tri)) continue;
    for (int z = tri.range[2].first; z <= tri.range[2].last; ++z)
      for (int y = tri.range[1].first; y <= tri.range[1].last; ++y)
        for (int x = tri.range[0].first; x <= tri.range[0].last; ++x)
          if (sat_voxel_passes(tri, ivec3(x, y, z))) out.insert({x, y, z});
  }
  return out;
}

inline int64_t count_differences(const VoxelSet& a, const VoxelSet& b) {
  int64_t d = 0;
  for (const Voxel& v : a) d += !b.count(v);
  for (const Voxel& v : b) d += !a.count(v);
  return d;
}

}  // namespace dv::test
