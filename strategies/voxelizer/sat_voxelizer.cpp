// The `sat` conservative voxelizer's passes (test and work split in sat_kernels.h), one source
// for both backends (nvcc compiles this file when CUDA is on):
//   clear    a fresh zeroed grid;
//   setup    per triangle: corners to grid coordinates, bounding range, work-item count;
//   scan     exclusive scan of the counts on the host (one int64 per triangle);
//   voxelize one thread per work item (a column or a slice of one triangle): it finds its
//            triangle by binary search over the offsets, rebuilds the triangle's test from its
//            three corners (cheaper than storing it) and ORs its voxels into the grid.
#include "strategies/voxelizer/sat_voxelizer.h"

#include <span>

#include "core/pass_timer.h"
#include "strategies/voxelizer/sat_kernels.h"

namespace dv {

VoxelizeResult voxelize_sat(Backend backend, const TriangleSoup& soup, const GridSpec& spec) {
  validate_grid_spec(spec, "sat voxelizer");
  require_backend(backend);
  const Memory memory = backend == Backend::cuda ? Memory::device : Memory::host;
  VoxelizeResult result;
  {
    PassTimer timer(backend);
    result.grid = VoxelGrid(spec, memory);
    result.passes.push_back({"clear", timer.stop()});
  }
  const int64_t triangles = soup.triangle_count();
  result.counters["triangles"] = triangles;
  if (triangles == 0) {
    result.counters["work_items"] = 0;
    result.counters["degenerate_triangles"] = 0;
    return result;
  }

  PassTimer upload_timer(backend);
  const Buffer<dvec3> world(memory,
                            std::span<const dvec3>(soup.corners.data(), size_t(3 * triangles)),
                            "sat world corners");
  result.passes.push_back({"upload", upload_timer.stop()});

  Buffer<dvec3> corners(memory, 3 * triangles, "sat grid corners");
  Buffer<int64_t> counts(memory, triangles, "sat work counts");
  Buffer<uint8_t> degenerate(memory, triangles, "sat degenerate flags");
  const GridTransform to_grid = grid_transform(spec);
  const ivec3 res = spec.res;
  {
    PassTimer timer(backend);
    const View<const dvec3> in = world.const_view();
    const View<dvec3> out = corners.view();
    const View<int64_t> count = counts.view();
    const View<uint8_t> flag = degenerate.view();
    parallel_for(
        backend, "sat_setup", triangles, DV_KERNEL_LAMBDA(int64_t i) {
          const dvec3 a = to_grid.apply(in[3 * i]), b = to_grid.apply(in[3 * i + 1]),
                      c = to_grid.apply(in[3 * i + 2]);
          out[3 * i] = a;
          out[3 * i + 1] = b;
          out[3 * i + 2] = c;
          SatTriangle t;
          sat_setup(a, b, c, res, t);
          count[i] = t.work_items;
          flag[i] = t.work_items > 0 && t.degenerate ? 1 : 0;
        });
    result.passes.push_back({"setup", timer.stop()});
  }

  std::vector<int64_t> offsets(size_t(triangles) + 1);
  int64_t degenerate_count = 0;
  {
    PassTimer timer(backend);
    const std::vector<int64_t> host_counts = counts.to_vector();
    int64_t total = 0;
    for (int64_t i = 0; i < triangles; ++i) {
      offsets[size_t(i)] = total;
      total += host_counts[size_t(i)];
    }
    offsets[size_t(triangles)] = total;
    for (uint8_t f : degenerate.to_vector()) degenerate_count += f;
    result.passes.push_back({"scan", timer.stop()});
  }
  const int64_t work_items = offsets.back();
  result.counters["work_items"] = work_items;
  result.counters["degenerate_triangles"] = degenerate_count;

  const Buffer<int64_t> offset_buffer(memory, std::span<const int64_t>(offsets), "sat offsets");
  {
    PassTimer timer(backend);
    const View<const dvec3> in = corners.const_view();
    const View<const int64_t> first = offset_buffer.const_view();
    const VoxelGridView grid = result.grid.view();
    parallel_for(
        backend, "sat_voxelize", work_items, DV_KERNEL_LAMBDA(int64_t i) {
          // The last triangle whose first item is <= i (triangles without items share offsets).
          int64_t lo = 0, hi = triangles - 1;
          while (lo < hi) {
            const int64_t mid = (lo + hi + 1) / 2;
            if (first[mid] <= i)
              lo = mid;
            else
              hi = mid - 1;
          }
          SatTriangle t;
          sat_setup(in[3 * lo], in[3 * lo + 1], in[3 * lo + 2], res, t);
          sat_work_item(t, i - first[lo], grid);
        });
    result.passes.push_back({"voxelize", timer.stop()});
  }
  return result;
}

}  // namespace dv
