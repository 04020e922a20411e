// The atlas voxelizers' passes (see atlas_voxelizer.h); nvcc compiles this file when CUDA is on.
// The position texture is side x side dvec4 texels: world position and w = 1 where a triangle
// covers the texel centre, all zero elsewhere.
#include "strategies/voxelizer/atlas_voxelizer.h"

#include <memory>
#include <nlohmann/json.hpp>
#include <span>

#include "cuda/pass_timer.h"
#include "strategies/voxelizer/atlas_device.h"
#include "strategies/voxelizer/atlas_packing.h"
#include "strategies/voxelizer/raster_input.h"
#include "strategies/voxelizer/work_items.h"

namespace dv {

namespace {

// What both methods share: the grid, the layout and the triangles and cells in backend memory.
struct AtlasSetup {
  Memory memory = Memory::host;
  AtlasLayout layout;
  Buffer<dvec3> corners;
  Buffer<AtlasCell> cells;
};

AtlasSetup setup_atlas(Backend backend, const TriangleSoup& soup, const GridSpec& spec,
                       int atlas_side, const char* where, VoxelizeResult& result) {
  validate_grid_spec(spec, where);
  require_backend(backend);
  AtlasSetup s;
  s.memory = memory_of(backend);
  {
    PassTimer timer(backend);
    result.grid = VoxelGrid(spec, s.memory);
    result.passes.push_back({"clear", timer.stop()});
  }
  {
    PassTimer timer(Backend::cpu);
    s.layout = pack_atlas(soup, spec, atlas_side);
    result.passes.push_back({"pack", timer.stop()});
  }
  {
    PassTimer timer(backend);
    s.corners = Buffer<dvec3>(s.memory, std::span<const dvec3>(soup.corners), "atlas corners");
    s.cells =
        Buffer<AtlasCell>(s.memory, std::span<const AtlasCell>(s.layout.cells), "atlas cells");
    result.passes.push_back({"upload", timer.stop()});
  }
  result.counters["triangles"] = soup.triangle_count();
  result.counters["atlas_side"] = atlas_side;
  result.counters["texel_size"] = s.layout.texel_size;
  result.counters["valid_texels"] = s.layout.valid_texels();
  return s;
}

}  // namespace

VoxelizeResult voxelize_atlas(Backend backend, const TriangleSoup& soup, const GridSpec& spec,
                              int atlas_side) {
  const int64_t triangles = soup.triangle_count();
  check_raster_triangle_count(triangles, "atlas voxelizer");
  VoxelizeResult result;
  const AtlasSetup s = setup_atlas(backend, soup, spec, atlas_side, "atlas voxelizer", result);
  if (triangles == 0) return result;
  const int64_t texels = int64_t(atlas_side) * atlas_side;
  Buffer<dvec4> positions(s.memory, texels, "atlas position texture");
  {
    PassTimer timer(backend);
    positions.fill_zero();
    RasterInput input(s.memory, triangles);
    const View<const AtlasCell> cells = s.cells.const_view();
    const View<dvec3> out = input.vertices.view();
    const View<u32vec3> index = input.triangles.view();
    parallel_for(
        backend, "atlas_setup", triangles, DV_KERNEL_LAMBDA(int64_t i) {
          for (int m = 0; m < 3; ++m) out[3 * i + m] = atlas_corner_position(cells[i], m);
          const uint32_t first = uint32_t(3 * i);
          index[i] = u32vec3(first, first + 1, first + 2);
        });
    const TileLists lists =
        rasterize_tiles(backend, input.view(make_screen_projection(atlas_side, atlas_side)));
    check_tile_lists(lists, "atlas voxelizer");
    result.counters["raster"] = lists.stats;
    const TileListsView tiles = lists.view();
    const View<const dvec3> corners = s.corners.const_view();
    const View<dvec4> texture = positions.view();
    const int side = atlas_side;
    parallel_for(
        backend, "atlas_update", texels, DV_KERNEL_LAMBDA(int64_t p) {
          const int x = int(p % side), y = int(p / side);
          bool done = false;
          for_each_fragment(tiles, x, y, [&](uint32_t tri) {
            if (done) return;  // cells are disjoint: at most one triangle covers a texel
            const AtlasCell cell = cells[tri];
            texture[p] =
                dvec4(atlas_point(&corners[3 * int64_t(tri)], cell, x - cell.x, y - cell.y), 1.0);
            done = true;
          });
        });
    result.passes.push_back({"atlas_update", timer.stop()});
  }
  {
    PassTimer timer(backend);
    const GridTransform to_grid = grid_transform(spec);
    const View<const dvec4> texture = positions.const_view();
    const VoxelGridView grid = result.grid.view();
    parallel_for(
        backend, "atlas_points", texels, DV_KERNEL_LAMBDA(int64_t p) {
          const dvec4 t = texture[p];
          if (t.w != 0.0) atlas_write_point(grid, to_grid, dvec3(t));
        });
    result.passes.push_back({"points", timer.stop()});
  }
  return result;
}

VoxelizeResult voxelize_atlas_compute(Backend backend, const TriangleSoup& soup,
                                      const GridSpec& spec, int atlas_side) {
  VoxelizeResult result;
  const AtlasSetup s =
      setup_atlas(backend, soup, spec, atlas_side, "atlas-compute voxelizer", result);
  const int64_t triangles = soup.triangle_count();
  if (triangles == 0) return result;
  const Buffer<int64_t> offsets(s.memory, std::span<const int64_t>(s.layout.texel_first),
                                "atlas texel offsets");
  {
    PassTimer timer(backend);
    const GridTransform to_grid = grid_transform(spec);
    const View<const dvec3> corners = s.corners.const_view();
    const View<const AtlasCell> cells = s.cells.const_view();
    const View<const int64_t> first = offsets.const_view();
    const VoxelGridView grid = result.grid.view();
    parallel_for(
        backend, "atlas_compute_points", s.layout.valid_texels(), DV_KERNEL_LAMBDA(int64_t k) {
          const int64_t tri = owner_of_item(first, triangles, k);
          int i, j;
          atlas_texel_of(k - first[tri], i, j);
          atlas_write_point(grid, to_grid, atlas_point(&corners[3 * tri], cells[tri], i, j));
        });
    result.passes.push_back({"points", timer.stop()});
  }
  return result;
}

namespace {

class AtlasVoxelizer : public Voxelizer {
 public:
  AtlasVoxelizer(bool compute, const StrategyParams& params)
      : compute_(compute), params_(params), side_(params.integer("atlas")) {}
  std::string name() const override { return compute_ ? "atlas-compute" : "atlas"; }
  nlohmann::json params() const override { return params_.echo(); }
  bool supports(Backend backend) const override {
    return backend == Backend::cpu || kBuiltWithCuda;
  }
  VoxelizeResult voxelize(Backend backend, const TriangleSoup& soup,
                          const GridSpec& spec) override {
    return compute_ ? voxelize_atlas_compute(backend, soup, spec, side_)
                    : voxelize_atlas(backend, soup, spec, side_);
  }

 private:
  bool compute_;
  StrategyParams params_;
  int side_;
};

}  // namespace

ParamSpec atlas_side_param() {
  return integer_param("atlas", kDefaultAtlasSide, 1, kMaxAtlasSide,
                       "texels per side of the triangle atlas (points per triangle follow)");
}

void register_atlas_voxelizers(Registry<Voxelizer>& registry) {
  registry.add("atlas",
               "one point per texel of a triangle atlas rasterized into a position texture "
               "(Thiedemann et al. 2011), CPU and CUDA",
               {atlas_side_param()},
               [](const StrategyParams& p) { return std::make_unique<AtlasVoxelizer>(false, p); });
  registry.add("atlas-compute",
               "the atlas points computed and written by a compute kernel, no rasterization "
               "(Buchacher 2014 3.4), CPU and CUDA",
               {atlas_side_param()},
               [](const StrategyParams& p) { return std::make_unique<AtlasVoxelizer>(true, p); });
}

}  // namespace dv
