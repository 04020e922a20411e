// Voxel grid storage, validation and the MIP reduction (see voxel_grid.h). Compiled by nvcc
// when CUDA is on, so mip_down runs as a kernel on device grids.
#include "strategies/voxelizer/voxel_grid.h"

#include <bit>
#include <cmath>

#include "core/error.h"

namespace dv {

void validate_grid_spec(const GridSpec& spec, const std::string& where) {
  const ivec3 r = spec.res;
  const std::string res =
      std::to_string(r.x) + "x" + std::to_string(r.y) + "x" + std::to_string(r.z);
  if (r.x <= 0 || r.y <= 0 || r.z <= 0)
    throw InputError(where, "resolution " + res + " must be positive on every axis");
  if (r.z % 32 != 0)
    throw InputError(where, "depth " + std::to_string(r.z) +
                                " must be a multiple of 32 (32 slices per 32-bit word)");
  if (r.x > kMaxGridSide || r.y > kMaxGridSide || r.z > kMaxGridDepth)
    throw InputError(where, "resolution " + res + " too big (at most " +
                                std::to_string(kMaxGridSide) + " in x and y, " +
                                std::to_string(kMaxGridDepth) + " in depth)");
  if (spec.voxel_count() > kMaxGridVoxels)
    throw InputError(where, "resolution " + res + " has more than 2^34 voxels");
  for (int a = 0; a < 3; ++a) {
    if (!std::isfinite(spec.bounds.lo[a]) || !std::isfinite(spec.bounds.hi[a]))
      throw InputError(where, "grid bounds are not finite");
    if (!(spec.bounds.hi[a] > spec.bounds.lo[a]))
      throw InputError(where, "grid bounds must have max > min on every axis");
  }
  if (spec.kind == GridKind::box) return;
  const GridFrustum& f = spec.frustum;
  if (!std::isfinite(f.near) || !std::isfinite(f.far) || !(f.far > f.near))
    throw InputError(where, "frustum grid depth range must be finite with far > near");
  if (spec.kind == GridKind::perspective && !(f.near > 0.0))
    throw InputError(where, "perspective grid must start in front of its eye (near > 0)");
  if (f.projection.width != r.x || f.projection.height != r.y ||
      f.projection.orthographic != (spec.kind == GridKind::orthographic))
    throw InputError(where, "frustum grid projection does not match its kind and resolution");
}

void require_affine_grid(const GridSpec& spec, const std::string& where) {
  if (!spec.affine())
    throw InputError(where,
                     "perspective (spot or omni light) grids are not supported: its cells are "
                     "frustum-shaped, not boxes; use a point method (slicemap, atlas, "
                     "atlas-compute)");
}

GridSpec make_box_grid(const ivec3& res, const Aabb& bounds, const std::string& where) {
  GridSpec spec;
  spec.kind = GridKind::box;
  spec.res = res;
  spec.bounds = bounds;
  validate_grid_spec(spec, where);
  return spec;
}

GridTransform grid_transform(const GridSpec& spec) {
  GridTransform t;
  if (spec.kind != GridKind::box) {
    const GridFrustum& f = spec.frustum;
    t.frustum = true;
    t.world_to_clip = f.projection.world_to_clip;
    t.scale = dvec3(spec.res);
    t.eye = f.eye;
    t.axis = f.axis;
    t.near = f.near;
    t.depth_scale = double(spec.res.z) / (f.far - f.near);
    return t;
  }
  t.lo = spec.bounds.lo;
  for (int a = 0; a < 3; ++a)
    t.scale[a] = double(spec.res[a]) / (spec.bounds.hi[a] - spec.bounds.lo[a]);
  return t;
}

VoxelGrid::VoxelGrid(const GridSpec& spec, Memory memory)
    : spec_(spec), words_(memory, spec.word_count(), "voxel grid") {
  words_.fill_zero();
}

VoxelGridView VoxelGrid::view() const {
  return {words_.data(), spec_.res.x, spec_.res.y, spec_.res.z};
}

int64_t VoxelGrid::popcount() const {
  int64_t count = 0;
  for (uint32_t w : words_.to_vector()) count += std::popcount(w);
  return count;
}

VoxelGrid VoxelGrid::copy_to(Memory memory) const {
  VoxelGrid out(spec_, memory);
  const std::vector<uint32_t> host = words_.to_vector();
  out.words_.upload(host);
  return out;
}

void VoxelGrid::check_host_voxel(int x, int y, int z, const char* what) const {
  if (memory() != Memory::host) throw Error(std::string("VoxelGrid::") + what + ": device grid");
  if (x < 0 || y < 0 || z < 0 || x >= spec_.res.x || y >= spec_.res.y || z >= spec_.res.z)
    throw Error(std::string("VoxelGrid::") + what + ": voxel outside the grid");
}

bool VoxelGrid::get(int x, int y, int z) const {
  check_host_voxel(x, y, z, "get");
  return view().get(x, y, z);
}

void VoxelGrid::set(int x, int y, int z) {
  check_host_voxel(x, y, z, "set");
  view().set(x, y, z);
}

VoxelGrid mip_down(const VoxelGrid& finer) {
  const GridSpec& f = finer.spec();
  if (f.kind != GridKind::box)
    throw InputError("voxel MIP levels", "only box grids have MIP levels, not light frustums");
  GridSpec coarse = f;
  coarse.res = ivec3((f.res.x + 1) / 2, (f.res.y + 1) / 2, f.res.z);
  const dvec3 unit = f.voxel_size();
  coarse.bounds.hi.x = f.bounds.lo.x + 2.0 * coarse.res.x * unit.x;
  coarse.bounds.hi.y = f.bounds.lo.y + 2.0 * coarse.res.y * unit.y;
  VoxelGrid out(coarse, finer.memory());
  const VoxelGridView src = finer.view(), dst = out.view();
  const int64_t texels = coarse.word_count();
  parallel_for(
      finer.backend(), "voxel_mip_down", texels, DV_KERNEL_LAMBDA(int64_t i) {
        const int x = int(i % dst.width);
        const int y = int((i / dst.width) % dst.height);
        const int k = int(i / (int64_t(dst.width) * dst.height));
        const int x1 = min_value(2 * x + 1, src.width - 1),
                  y1 = min_value(2 * y + 1, src.height - 1);
        uint32_t bits = 0;
        for (int sy = 2 * y; sy <= y1; ++sy)
          for (int sx = 2 * x; sx <= x1; ++sx) bits |= src.words[src.word_index(sx, sy, k)];
        dst.words[i] = bits;
      });
  return out;
}

std::vector<VoxelGrid> mip_chain(const VoxelGrid& base) {
  std::vector<VoxelGrid> levels;
  const VoxelGrid* current = &base;
  while (current->spec().res.x > 1 || current->spec().res.y > 1) {
    levels.push_back(mip_down(*current));
    current = &levels.back();
  }
  return levels;
}

}  // namespace dv
