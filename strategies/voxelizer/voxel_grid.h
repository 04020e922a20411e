// The binary voxel grid every voxelizer fills: W x H x D voxels over a world box, bit-packed
// along depth so that one 32-bit word holds 32 consecutive slices of one (x, y) column, the way
// a slicemap texel does (Eisemann & Decoret 2006; Buchacher 2014 §3).
//
// Conventions (grid coordinates are world coordinates mapped so that voxel (i, j, k) is the unit
// cube [i, i+1] x [j, j+1] x [k, k+1]):
//   - Voxel (i, j, k) covers [lo + i*unit, lo + (i+1)*unit) on each axis, half-open, except that
//     the last voxel of each axis also holds the box's closed upper face (a point exactly on
//     hi.x lands in voxel W-1). Points outside the closed box belong to no voxel.
//   - Conservative voxelizers (exact, sat) set every voxel whose CLOSED box meets a triangle, so
//     a face lying exactly on a voxel boundary sets the voxels on both sides of it.
//   - Light-frustum grids (kinds orthographic and perspective, built from a light's map face by
//     strategies/voxelizer/frustum_grid.h): grid x and y are the face's image coordinates
//     (pixel (x, y) of a W x H image is the column [x, x+1) x [y, y+1)), grid z is the depth
//     along the view axis, dot(p - eye, axis), mapped linearly from [near, far] to [0, D]: slices
//     are planes at equal distances along the axis. Orthographic grids are an affine image of
//     world space (cells are boxes in grid space); perspective ones are not (x and y divide by
//     the depth), so only the point methods can fill them.
//   - Memory layout: word (x, y, k) holds z = 32k .. 32k+31 (bit z & 31) and sits at index
//     (k * H + y) * W + x: a stack of D/32 slices of W x H words, like a layered integer texture.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/atomic.h"
#include "core/bits.h"
#include "core/math.h"
#include "cuda/buffer.h"
#include "cuda/execute.h"
#include "engine/raster/raster_projection.h"

namespace dv {

// Limits checked by validate_grid_spec: D any multiple of 32 up to kMaxGridDepth, W and H up to
// kMaxGridSide, and at most kMaxGridVoxels voxels (2 GiB of words).
inline constexpr int kMaxGridSide = 16384;
inline constexpr int kMaxGridDepth = 4096;
inline constexpr int64_t kMaxGridVoxels = int64_t(1) << 34;

// An axis-aligned box, or a light's frustum (see the file comment).
enum class GridKind : uint8_t { box, orthographic, perspective };

// The frustum of the light-frustum kinds: the face's projection (image res.x x res.y), the
// origin and unit axis of the depth, and the depth range the slices divide.
struct GridFrustum {
  RasterProjection projection;
  dvec3 eye{0.0};
  dvec3 axis{0.0, 0.0, 1.0};
  double near = 0.0, far = 1.0;
};

struct GridSpec {
  GridKind kind = GridKind::box;
  ivec3 res{0, 0, 0};   // W (x), H (y), D (z)
  Aabb bounds;          // world box the grid covers (frustum kinds: its bounding box)
  GridFrustum frustum;  // frustum kinds only

  // Box kind: the world size of a voxel.
  dvec3 voxel_size() const { return bounds.extent() / dvec3(res); }
  // Whether grid coordinates are an affine image of world space (box and orthographic).
  bool affine() const { return kind != GridKind::perspective; }
  int words_per_column() const { return res.z / 32; }
  int64_t word_count() const { return int64_t(res.x) * res.y * words_per_column(); }
  int64_t voxel_count() const { return int64_t(res.x) * res.y * res.z; }
};

// Throws InputError(where, ...) when the resolution breaks the limits above or the bounds are
// empty, flat or not finite.
void validate_grid_spec(const GridSpec& spec, const std::string& where);
// A validated axis-aligned box grid.
GridSpec make_box_grid(const ivec3& res, const Aabb& bounds, const std::string& where = "grid");

// Throws InputError(where) for a perspective grid: the conservative voxelizers (exact, sat) test
// box-shaped cells, and a perspective grid's cells are frustum-shaped in world space.
void require_affine_grid(const GridSpec& spec, const std::string& where);

// World -> grid coordinates: voxel (i, j, k) is [i, i+1]^3 there. Box grids: (p - lo) * scale
// per axis. Frustum grids: x and y from the projection (pixel units, rows down), z = (dot(p -
// eye, axis) - near) * depth_scale; NaN for points behind a perspective grid's eye.
struct GridTransform {
  bool frustum = false;
  dvec3 lo{0.0};
  dvec3 scale{1.0};
  dmat4 world_to_clip{1.0};
  dvec3 eye{0.0}, axis{0.0, 0.0, 1.0};
  double near = 0.0, depth_scale = 1.0;

  // Frustum grids: the world depth along the axis, and grid z.
  DV_HD double axial_depth(const dvec3& p) const {
    return (p.x - eye.x) * axis.x + (p.y - eye.y) * axis.y + (p.z - eye.z) * axis.z;
  }
  DV_HD double depth(const dvec3& p) const { return (axial_depth(p) - near) * depth_scale; }
  DV_HD dvec3 apply(const dvec3& p) const {
    if (!frustum)
      return dvec3((p.x - lo.x) * scale.x, (p.y - lo.y) * scale.y, (p.z - lo.z) * scale.z);
    const dmat4& m = world_to_clip;
    const double x = ((m[0][0] * p.x + m[1][0] * p.y) + m[2][0] * p.z) + m[3][0];
    const double y = ((m[0][1] * p.x + m[1][1] * p.y) + m[2][1] * p.z) + m[3][1];
    const double w = ((m[0][3] * p.x + m[1][3] * p.y) + m[2][3] * p.z) + m[3][3];
    if (!(w > 0.0)) return dvec3(NAN);
    return dvec3((x / w * 0.5 + 0.5) * scale.x, (0.5 - y / w * 0.5) * scale.y, depth(p));
  }
};
GridTransform grid_transform(const GridSpec& spec);

// What kernels receive: the words and the sizes. Setting bits is atomic (many threads write
// the same words); reads are plain.
struct VoxelGridView {
  uint32_t* words = nullptr;
  int width = 0, height = 0, depth = 0;

  DV_HD int64_t word_index(int x, int y, int k) const {
    return (int64_t(k) * height + y) * width + x;
  }
  DV_HD bool get(int x, int y, int z) const {
    return (words[word_index(x, y, z >> 5)] >> (z & 31)) & 1u;
  }
  DV_HD void set(int x, int y, int z) const {
    atomic_or(&words[word_index(x, y, z >> 5)], 1u << (z & 31));
  }
  // ORs `mask` into word `index` (word_index); an empty mask writes nothing.
  DV_HD void or_word(int64_t index, uint32_t mask) const {
    if (mask) atomic_or(&words[index], mask);
  }
  // Set voxels of column (x, y) in slices 0 .. z-1 (z in [0, depth]).
  DV_HD int count_below(int x, int y, int z) const {
    int count = 0;
    for (int k = 0; k < (z >> 5); ++k) count += bit_count(words[word_index(x, y, k)]);
    if (z & 31) count += bit_count(bits_below(words[word_index(x, y, z >> 5)], z & 31));
    return count;
  }
};

class VoxelGrid {
 public:
  VoxelGrid() = default;
  // A cleared grid in host or device memory; the spec must be valid (validate_grid_spec).
  VoxelGrid(const GridSpec& spec, Memory memory);

  const GridSpec& spec() const { return spec_; }
  Memory memory() const { return words_.memory(); }
  // The backend that can run kernels on this grid's memory.
  Backend backend() const { return memory() == Memory::device ? Backend::cuda : Backend::cpu; }
  VoxelGridView view() const;

  void clear() { words_.fill_zero(); }
  // Set voxels (copies device grids to the host to count them).
  int64_t popcount() const;
  std::vector<uint32_t> words() const { return words_.to_vector(); }
  // A copy of the grid in `memory`.
  VoxelGrid copy_to(Memory memory) const;

  // Single-voxel access for host grids (throws Error for device grids or outside the grid).
  bool get(int x, int y, int z) const;
  void set(int x, int y, int z);

 private:
  void check_host_voxel(int x, int y, int z, const char* what) const;

  GridSpec spec_;
  Buffer<uint32_t> words_;
};

// One MIP level down (Buchacher §3.5; box grids only, frustum grids throw InputError): texel (x, y)
// of the result ORs texels 2x..2x+1, 2y..2y+1 of `finer` with all depth bits kept. Odd sizes round
// up, so the last row and column are never lost: the result is ceil(W/2) x ceil(H/2) x D and its
// bounds grow to lo + 2 * ceil(W/2) * unit so its voxels are exactly twice as wide. Runs where the
// grid lives.
VoxelGrid mip_down(const VoxelGrid& finer);
// Levels 1, 2, ... down to 1 x 1 (level 0, the grid itself, is not repeated).
std::vector<VoxelGrid> mip_chain(const VoxelGrid& base);

}  // namespace dv
