// The `sat` conservative voxelizer's passes (test and work split in sat_kernels.h), one source
// for both backends (nvcc compiles this file when CUDA is on):
//   clear    a fresh zeroed grid;
//   upload   the triangles' corners;
//   setup    allocation of the counts, then per triangle: corners to grid coordinates (in
//            place), bounding range, work-item count, and a count of the degenerate ones;
//   scan     exclusive scan of the counts where they live (cuda/scan.h), then one read-back of
//            the total and the degenerate count (the total sizes the next launch);
//   voxelize one thread per work item (a column or a slice of one triangle): it finds its
//            triangle by binary search over the offsets, rebuilds the triangle's test from its
//            three corners (cheaper than storing it) and ORs its voxels into the grid.
// Per call the backend memory holds the grid, the corners and one int64 per triangle plus two.
#include "strategies/voxelizer/sat_voxelizer.h"

#include <cstring>
#include <memory>
#include <span>

#include "core/atomic.h"
#include "cuda/pass_timer.h"
#include "cuda/scan.h"
#include "strategies/voxelizer/sat_device.h"
#include "strategies/voxelizer/work_items.h"

namespace dv {

namespace {

// values[first] and values[first + 1] set to zero / copied to the host.
void write_tail_zeros(Buffer<int64_t>& values, int64_t first) {
  if (values.memory() == Memory::device)
    device_memset(values.data() + first, 0, 2 * sizeof(int64_t));
  else
    std::memset(values.data() + first, 0, 2 * sizeof(int64_t));
}
void read_tail(const Buffer<int64_t>& values, int64_t first, int64_t out[2]) {
  if (values.memory() == Memory::device)
    copy_to_host(out, values.data() + first, 2 * sizeof(int64_t));
  else
    std::memcpy(out, values.data() + first, 2 * sizeof(int64_t));
}

}  // namespace

VoxelizeResult voxelize_sat(Backend backend, const TriangleSoup& soup, const GridSpec& spec) {
  validate_grid_spec(spec, "sat voxelizer");
  require_affine_grid(spec, "sat voxelizer");
  require_backend(backend);
  const Memory memory = memory_of(backend);
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
  Buffer<dvec3> corners(memory, std::span<const dvec3>(soup.corners.data(), size_t(3 * triangles)),
                        "sat corners");
  result.passes.push_back({"upload", upload_timer.stop()});

  // counts: [0, triangles) work items per triangle, then offsets after the scan;
  // [triangles] 0, the total after the scan; [triangles + 1] degenerate triangles.
  Buffer<int64_t> counts;
  const GridTransform to_grid = grid_transform(spec);
  const ivec3 res = spec.res;
  {
    PassTimer timer(backend);
    counts = Buffer<int64_t>(memory, triangles + 2, "sat work counts");
    write_tail_zeros(counts, triangles);
    const View<dvec3> corner = corners.view();
    const View<int64_t> count = counts.view();
    // The slot is zeroed, added to and copied out as bytes, never read as an int64_t.
    auto* const degenerate = reinterpret_cast<unsigned long long*>(counts.data() + triangles + 1);
    parallel_for(
        backend, "sat_setup", triangles, DV_KERNEL_LAMBDA(int64_t i) {
          const dvec3 a = to_grid.apply(corner[3 * i]), b = to_grid.apply(corner[3 * i + 1]),
                      c = to_grid.apply(corner[3 * i + 2]);
          corner[3 * i] = a;
          corner[3 * i + 1] = b;
          corner[3 * i + 2] = c;
          SatTriangle t;
          sat_setup(a, b, c, res, t);
          count[i] = t.work_items;
          if (t.work_items > 0 && t.degenerate) atomic_add(degenerate, 1ull);
        });
    result.passes.push_back({"setup", timer.stop()});
  }

  int64_t tail[2];
  {
    PassTimer timer(backend);
    exclusive_scan_queued(backend, View<int64_t>{counts.data(), triangles + 1});
    read_tail(counts, triangles, tail);
    result.passes.push_back({"scan", timer.stop()});
  }
  const int64_t work_items = tail[0];
  result.counters["work_items"] = work_items;
  result.counters["degenerate_triangles"] = tail[1];

  {
    PassTimer timer(backend);
    const View<const dvec3> in = corners.const_view();
    const View<const int64_t> first = counts.const_view();
    const VoxelGridView grid = result.grid.view();
    parallel_for(
        backend, "sat_voxelize", work_items, DV_KERNEL_LAMBDA(int64_t i) {
          const int64_t lo = work_item_owner(first, triangles, i);
          SatTriangle t;
          sat_setup(in[3 * lo], in[3 * lo + 1], in[3 * lo + 2], res, t);
          sat_work_item(t, i - first[lo], grid);
        });
    result.passes.push_back({"voxelize", timer.stop()});
  }
  return result;
}

void register_sat_voxelizer(Registry<Voxelizer>& registry) {
  registry.add("sat",
               "conservative surface voxelization, plane + 2D edge tests (Schwarz & Seidel "
               "2010), CPU and CUDA",
               [](const StrategyParams&) {
                 return std::make_unique<FunctionVoxelizer>("sat", voxelize_sat, true);
               });
}

}  // namespace dv
