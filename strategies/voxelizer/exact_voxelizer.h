// The CPU reference voxelization `exact`: every voxel whose closed box overlaps a triangle,
// decided by the 13-axis separating-axis test of Akenine-Moller (2001) in double precision
// (3 box normals, the triangle normal, 9 edge x box-axis cross products). A degenerate triangle
// (see voxel_geometry.h) has no usable normal: that axis is skipped and the other twelve decide,
// which is the complete separating-axis set of the segment or point it collapses to.
//
// Alongside the exact set it computes the borderline band the metrics need: a voxel is
// borderline when some triangle meets its box grown by kBorderlineBand voxel on every side but
// no triangle meets its box shrunk by kBorderlineBand, i.e. its membership depends on rounding.
#pragma once

#include "strategies/voxelizer/triangle_soup.h"
#include "strategies/voxelizer/voxel_grid.h"
#include "strategies/voxelizer/voxelizer.h"

namespace dv {

inline constexpr double kBorderlineBand = 1e-4;  // voxels

struct ExactVoxelization {
  VoxelGrid exact;   // closed voxel boxes meeting a triangle
  VoxelGrid grown;   // boxes grown by kBorderlineBand meeting a triangle (empty without band)
  VoxelGrid shrunk;  // boxes shrunk by kBorderlineBand meeting a triangle (empty without band)
  double milliseconds = 0.0;
};

// Separating-axis test in grid coordinates: does the closed box center +- half meet triangle
// (v0, v1, v2)? `use_normal` false skips the triangle-normal axis (degenerate triangles).
bool triangle_box_overlap(const dvec3& v0, const dvec3& v1, const dvec3& v2, const dvec3& normal,
                          bool use_normal, const dvec3& center, const dvec3& half);

// Host grids. with_band false fills only `exact` (about three times faster).
ExactVoxelization voxelize_exact(const TriangleSoup& soup, const GridSpec& spec,
                                 bool with_band = true);

}  // namespace dv
