// The `sat` conservative voxelizer's passes (test and work split in sat_device.h), one source
// for both backends (nvcc compiles this file when CUDA is on):
//   upload   the triangles' corners (timed alone: a copy the host waits for);
//   clear    a fresh zeroed grid, the zeroed counters and the large triangles' list;
//   small    one thread per triangle: corners to grid coordinates, the triangle's test and its
//            work items (voxel columns, or slices of a degenerate one); a triangle with at most
//            `small_items` of them is voxelized right there, a larger one stores its grid
//            corners (in place) and is appended to the large list (work_items.h's
//            PackedWorkList: entry and first item from one atomic add, no scan);
//   large    one wave of persistent threads loops over the large triangles' work items (the
//            count is read on the device, never by the host): each finds its triangle by binary
//            search over the list's first items, rebuilds the triangle's test when the triangle
//            changes and ORs one column's (or slice's) voxels into the grid.
// clear, small and large are queued back to back and timed by one PassTimeline, with no wait
// between them. The counters (small work items, degenerate triangles, the list's packed count)
// are read back once, after the last pass. Every route sets exactly the voxels that pass
// sat_voxel_passes, so the grid does not depend on the split. Per call the backend memory holds the
// grid, the corners and two int64 per triangle for the list.
#include "strategies/voxelizer/sat_voxelizer.h"

#include <algorithm>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "core/atomic.h"
#include "cuda/execute.h"
#include "cuda/pass_timer.h"
#include "strategies/voxelizer/sat_device.h"
#include "strategies/voxelizer/work_items.h"

namespace dv {

namespace {

// Consecutive work items of the large pass taken by 32 threads together (see its comment).
constexpr int64_t kSatLargeChunk = 256;

// counters[kSmallItems]: work items of the small triangles; [kDegenerate]: degenerate triangles
// with work; [kFirstList + b]: the packed count of batch b's large list.
enum SatCounter : int64_t { kSmallItems = 0, kDegenerate = 1, kFirstList = 2 };

// The most work items one triangle can have in a `res` grid (columns across two axes, or the
// slices along one).
int64_t max_sat_work_items(const ivec3& res) {
  const int64_t x = res.x, y = res.y, z = res.z;
  return std::max({x * y, y * z, x * z, x, y, z});
}

}  // namespace

void validate_sat_small_items(int64_t small_items) {
  if (small_items < 0 || small_items > kSatMaxSmallItems)
    throw InputError("voxelizer 'sat'", "small=" + std::to_string(small_items) +
                                            " must be in [0, " + std::to_string(kSatMaxSmallItems) +
                                            "] (work items of a triangle voxelized by one thread)");
}

VoxelizeResult voxelize_sat(Backend backend, const TriangleSoup& soup, const GridSpec& spec,
                            int64_t small_items, int64_t max_batch) {
  validate_grid_spec(spec, "sat voxelizer");
  require_affine_grid(spec, "sat voxelizer");
  require_backend(backend);
  validate_sat_small_items(small_items);
  const Memory memory = memory_of(backend);
  const int64_t triangles = soup.triangle_count();
  const ivec3 res = spec.res;
  // Triangles per large list: one list for any mesh and grid that are not both enormous.
  int64_t batch = packed_work_list_batch(triangles, max_sat_work_items(res));
  if (max_batch > 0) batch = std::min(batch, max_batch);
  const int64_t batches = triangles == 0 ? 0 : (triangles + batch - 1) / batch;
  VoxelizeResult result;
  result.counters["triangles"] = triangles;
  Buffer<dvec3> corners;
  if (triangles > 0) {
    PassTimer upload_timer(backend);
    corners = Buffer<dvec3>(
        memory, std::span<const dvec3>(soup.corners.data(), size_t(3 * triangles)), "sat corners");
    result.passes.push_back({"upload", upload_timer.stop()});
  }
  // After the upload the passes run back to back, timed with one wait at the end.
  PassTimeline timeline(backend);
  const auto take_passes = [&] {
    for (auto& [name, ms] : timeline.finish()) result.passes.push_back({name, ms});
  };
  result.grid = VoxelGrid(spec, memory);
  Buffer<unsigned long long> counters(memory, kFirstList + batches, "sat counters");
  counters.fill_zero();
  Buffer<int64_t> large_triangle(memory, triangles, "sat large triangles");
  Buffer<int64_t> large_first(memory, triangles, "sat large first items");
  timeline.mark("clear");
  if (triangles == 0) {
    take_passes();
    result.counters["work_items"] = 0;
    result.counters["large_triangles"] = 0;
    result.counters["degenerate_triangles"] = 0;
    return result;
  }

  const GridTransform to_grid = grid_transform(spec);
  const VoxelGridView grid = result.grid.view();
  const int item_bits = packed_item_bits(batch);
  const auto list_of = [&](int64_t b) {
    return PackedWorkList{counters.data() + kFirstList + b, large_triangle.data() + b * batch,
                          large_first.data() + b * batch, item_bits};
  };
  {
    const View<dvec3> corner = corners.view();
    unsigned long long* const small_count = counters.data() + kSmallItems;
    unsigned long long* const degenerate_count = counters.data() + kDegenerate;
    for (int64_t b = 0; b < batches; ++b) {
      const int64_t begin = b * batch;
      const PackedWorkList list = list_of(b);
      parallel_for(
          backend, "sat_small", std::min(batch, triangles - begin), DV_KERNEL_LAMBDA(int64_t j) {
            const int64_t i = begin + j;
            const dvec3 p0 = to_grid.apply(corner[3 * i]), p1 = to_grid.apply(corner[3 * i + 1]),
                        p2 = to_grid.apply(corner[3 * i + 2]);
            SatTriangle t;
            unsigned long long small = 0, degenerate = 0;
            if (sat_setup(p0, p1, p2, res, t) && t.work_items > 0) {
              degenerate = t.degenerate ? 1 : 0;
              if (t.work_items <= small_items) {
                sat_all_work_items(sat_walk(t), grid);
                small = static_cast<unsigned long long>(t.work_items);
              } else {
                corner[3 * i] = p0;
                corner[3 * i + 1] = p1;
                corner[3 * i + 2] = p2;
                list.append(i, t.work_items);
              }
            }
            atomic_add_combined(small_count, small);
            atomic_add_combined(degenerate_count, degenerate);
          });
    }
    timeline.mark("small");
  }
  {
    const View<const dvec3> in = corners.const_view();
    for (int64_t b = 0; b < batches; ++b) {
      const PackedWorkList list = list_of(b);
      parallel_for_resident(
          backend, "sat_large", DV_KERNEL_LAMBDA(int64_t i, int64_t threads) {
            const int64_t items = list.items();
            const View<const int64_t> first = list.firsts();
            // Each group of 32 threads takes chunks of kSatLargeChunk consecutive items, its
            // threads interleaved, and the groups' chunks interleave: a thread rebuilds a test
            // only where its chunk enters another triangle (its items only increase), and the
            // chunks in flight at once are neighbours in the list, so are their voxels.
            const int64_t group = i / 32, lane = i % 32, groups = threads / 32;
            int64_t owner = -1, owner_end = 0;
            SatWalk walk;
            for (int64_t chunk = group * kSatLargeChunk; chunk < items;
                 chunk += groups * kSatLargeChunk) {
              const int64_t end = min_value(items, chunk + kSatLargeChunk);
              for (int64_t k = chunk + lane; k < end; k += 32) {
                if (k >= owner_end) {
                  owner = owner_of_item(first, first.size, k);
                  owner_end = owner + 1 < first.size ? first[owner + 1] : items;
                  const int64_t tri = list.primitive[owner];
                  SatTriangle t;
                  sat_setup(in[3 * tri], in[3 * tri + 1], in[3 * tri + 2], res, t);
                  walk = sat_walk(t);
                }
                sat_work_item(walk, k - first[owner], grid);
              }
            }
          });
    }
    timeline.mark("large");
  }
  take_passes();

  std::vector<unsigned long long> counts = counters.to_vector();
  int64_t work_items = int64_t(counts[kSmallItems]), large = 0;
  for (int64_t b = 0; b < batches; ++b) {
    const PackedWorkList list{&counts[size_t(kFirstList + b)], nullptr, nullptr, item_bits};
    large += list.entries();
    work_items += list.items();
  }
  result.counters["work_items"] = work_items;
  result.counters["large_triangles"] = large;
  result.counters["degenerate_triangles"] = int64_t(counts[kDegenerate]);
  return result;
}

namespace {

class SatVoxelizer : public Voxelizer {
 public:
  explicit SatVoxelizer(const StrategyParams& params)
      : params_(params), small_items_(params.integer("small")) {}
  std::string name() const override { return "sat"; }
  nlohmann::json params() const override { return params_.echo(); }
  bool supports(Backend backend) const override {
    return backend == Backend::cpu || kBuiltWithCuda;
  }
  VoxelizeResult voxelize(Backend backend, const TriangleSoup& soup,
                          const GridSpec& spec) override {
    return voxelize_sat(backend, soup, spec, small_items_);
  }

 private:
  StrategyParams params_;
  int64_t small_items_;
};

}  // namespace

void register_sat_voxelizer(Registry<Voxelizer>& registry) {
  registry.add("sat",
               "conservative surface voxelization, plane + 2D edge tests (Schwarz & Seidel "
               "2010), CPU and CUDA",
               {integer_param("small", int(kSatSmallItems), 0, int(kSatMaxSmallItems),
                              "work items (voxel columns) of a triangle voxelized by one "
                              "thread; larger ones are split")},
               [](const StrategyParams& p) { return std::make_unique<SatVoxelizer>(p); });
}

}  // namespace dv
