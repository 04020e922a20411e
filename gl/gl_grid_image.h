// The voxel grid as an OpenGL r32ui 2D array image, shared by the GL voxelizers (slicemap,
// atlas) so that they allocate, clear, write and read back grids the same way: layer k holds
// slices 32k..32k+31 of every column, exactly VoxelGrid's word layout, so any depth that is a
// multiple of 32 works (up to the driver's array-layer limit; 1024 needs 32 layers). Shaders
// include kGridImageGlsl and set voxels with imageAtomicOr. Needs a current OpenGL 4.5 context.
#pragma once

#include <string>

#include "strategies/voxelizer/voxel_grid.h"

namespace dv::gl {

// glGetIntegerv of one implementation limit.
int gl_limit(unsigned name);

// Throws InputError(where) when a width x height target exceeds `limit` texels per side; `what`
// names it in the message ("grid", "atlas").
void require_side(const std::string& where, const std::string& what, int width, int height,
                  int limit);

// GLSL (after the #version line): the grid image at image unit 0, `uniform ivec3 grid_res`, and
//   int point_voxel(float g, int res)  the half-open cell holding g (voxel_geometry.h's rule: the
//                                      upper face belongs to the last cell; -1 outside [0, res]
//                                      or NaN)
//   void set_voxel(ivec3 v)            ORs voxel v's bit into its word
extern const char* const kGridImageGlsl;

class GridImage {
 public:
  // A cleared grid image for `spec`; throws InputError(where) beyond the driver's texture size
  // or array-layer limits.
  GridImage(const GridSpec& spec, const std::string& where);
  ~GridImage();
  GridImage(const GridImage&) = delete;
  GridImage& operator=(const GridImage&) = delete;

  // Binds the image to unit 0 and sets grid_res of `program`, which must be in use.
  void bind(unsigned program) const;
  // Waits for the shaders' image writes and copies the layers into `grid` (host, same spec).
  void read_into(VoxelGrid& grid) const;

 private:
  GridSpec spec_;
  unsigned texture_ = 0;
};

}  // namespace dv::gl
