// The `slicemap` voxelizer's passes on the CPU or CUDA backend (see slicemap_voxelizer.h); nvcc
// compiles this file when CUDA is on:
//   setup   corners to grid coordinates (the rasterizer's screen projection then maps grid x, y
//           to pixel x, y: pixel centres at k + 0.5) and the index list; perspective grids keep
//           world corners and rasterize with the grid's projection instead (grid coordinates
//           are not affine there: a triangle's depth is not linear in grid x, y);
//   raster  the shared tile rasterizer's per-tile fragment lists;
//   slices  one thread per pixel: for each covering triangle, its depth where the pixel's ray
//           (along +z through the pixel centre; perspective: the projection's pixel ray in
//           world space) meets its plane (engine/scene/ray_query.h triangle_plane_hit) picks the
//           slice, whose bit is ORed into the pixel's column.
#include "strategies/voxelizer/slicemap_voxelizer.h"

#include <memory>
#include <nlohmann/json.hpp>
#include <span>

#include "cuda/pass_timer.h"
#include "engine/scene/ray_query.h"
#include "strategies/voxelizer/raster_input.h"
#include "strategies/voxelizer/voxel_geometry.h"

namespace dv {

namespace {

// Where the slices pass looks: along +z in grid coordinates (affine grids), or along the
// perspective grid's pixel rays in world space with grid depth from the hit point.
struct SliceRays {
  bool world = false;
  RasterProjection projection;
  GridTransform to_grid;

  DV_HD PixelRay ray(int x, int y) const {
    if (world) return pixel_ray(projection, x, y);
    return {dvec3(double(x) + 0.5, double(y) + 0.5, 0.0), dvec3(0.0, 0.0, 1.0)};
  }
  DV_HD double slice_coordinate(const PixelRay& r, double t) const {
    return world ? to_grid.depth(r.origin + r.direction * t) : t;
  }
};

}  // namespace

VoxelizeResult voxelize_slicemap(Backend backend, const TriangleSoup& soup, const GridSpec& spec) {
  validate_grid_spec(spec, "slicemap voxelizer");
  require_backend(backend);
  const int64_t triangles = soup.triangle_count();
  check_raster_triangle_count(triangles, "slicemap voxelizer");
  const Memory memory = memory_of(backend);
  VoxelizeResult result;
  {
    PassTimer timer(backend);
    result.grid = VoxelGrid(spec, memory);
    result.passes.push_back({"clear", timer.stop()});
  }
  result.counters["triangles"] = triangles;
  if (triangles == 0) {
    result.counters["zero_area_triangles"] = 0;
    return result;
  }

  PassTimer upload_timer(backend);
  const Buffer<dvec3> world(memory,
                            std::span<const dvec3>(soup.corners.data(), size_t(3 * triangles)),
                            "slicemap world corners");
  result.passes.push_back({"upload", upload_timer.stop()});

  RasterInput input(memory, triangles);
  {
    PassTimer timer(backend);
    const GridTransform to_grid = grid_transform(spec);
    const bool keep_world = !spec.affine();
    const View<const dvec3> in = world.const_view();
    const View<dvec3> out = input.vertices.view();
    const View<u32vec3> index = input.triangles.view();
    parallel_for(
        backend, "slicemap_setup", triangles, DV_KERNEL_LAMBDA(int64_t i) {
          for (int k = 0; k < 3; ++k)
            out[3 * i + k] = keep_world ? in[3 * i + k] : to_grid.apply(in[3 * i + k]);
          const uint32_t first = uint32_t(3 * i);
          index[i] = u32vec3(first, first + 1, first + 2);
        });
    result.passes.push_back({"setup", timer.stop()});
  }

  const SliceRays rays{!spec.affine(), spec.frustum.projection, grid_transform(spec)};
  const RasterProjection projection =
      rays.world ? rays.projection : make_screen_projection(spec.res.x, spec.res.y);
  TileLists lists;
  {
    PassTimer timer(backend);
    lists = rasterize_tiles(backend, input.view(projection));
    result.passes.push_back({"raster", timer.stop()});
  }
  check_tile_lists(lists, "slicemap voxelizer");
  result.counters["zero_area_triangles"] = lists.stats.culled_degenerate;
  result.counters["raster"] = lists.stats;

  {
    PassTimer timer(backend);
    SceneView scene{};
    scene.vertices = input.vertices.const_view();
    scene.triangles = input.triangles.const_view();
    const TileListsView tiles = lists.view();
    const VoxelGridView grid = result.grid.view();
    parallel_for(
        backend, "slicemap_slices", int64_t(grid.width) * grid.height, DV_KERNEL_LAMBDA(int64_t p) {
          const int x = int(p % grid.width), y = int(p / grid.width);
          const PixelRay ray = rays.ray(x, y);
          for_each_fragment(tiles, x, y, [&](uint32_t tri) {
            double t;
            bool entering;
            if (!triangle_plane_hit(scene, tri, ray.origin, ray.direction, t, entering)) return;
            const int z = point_voxel(rays.slice_coordinate(ray, t), grid.depth);
            if (z >= 0) grid.set(x, y, z);
          });
        });
    result.passes.push_back({"slices", timer.stop()});
  }
  return result;
}

void register_slicemap_voxelizer(Registry<Voxelizer>& registry) {
  registry.add("slicemap",
               "slices of the fragments rasterized along +z, one bit per fragment (Eisemann & "
               "Decoret 2006), CPU and CUDA; OpenGL with --backend gl",
               {}, [](const StrategyParams&) {
                 return std::make_unique<FunctionVoxelizer>("slicemap", voxelize_slicemap, true);
               });
}

}  // namespace dv
