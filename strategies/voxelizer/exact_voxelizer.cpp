// The exact reference voxelization (see exact_voxelizer.h). Each triangle's voxel bounding
// range is cut into blocks of at most 32^3 voxels, the blocks are spread over the CPU threads,
// and each block is refined by halving: a sub-block the triangle does not meet (with its box
// grown by the band and a little slack) is dropped whole, single voxels get the full test up to
// three times (grown, exact, shrunk). The pruning uses the same separating-axis test on larger
// boxes, so the result is that of testing every voxel.
#include "strategies/voxelizer/exact_voxelizer.h"

#include <chrono>
#include <cmath>
#include <memory>

#include "core/parallel.h"
#include "strategies/voxelizer/voxel_geometry.h"

namespace dv {

namespace {

constexpr int kBlockSide = 32;
// Blocks are pruned with their box grown by this much more (voxels), so that rounding in the
// test of a large box can never drop a voxel whose own test passes.
constexpr double kPruneSlack = 1e-6;

// Projections of the three (box-centred) corners onto `axis` against the box radius.
bool separated_on(const dvec3& axis, const dvec3& a0, const dvec3& a1, const dvec3& a2,
                  const dvec3& half) {
  const double p0 = glm::dot(axis, a0), p1 = glm::dot(axis, a1), p2 = glm::dot(axis, a2);
  const double r =
      half.x * std::abs(axis.x) + half.y * std::abs(axis.y) + half.z * std::abs(axis.z);
  return std::min({p0, p1, p2}) > r || std::max({p0, p1, p2}) < -r;
}

struct ExactTriangle {
  dvec3 v0, v1, v2, normal;
  bool use_normal;
};

struct Block {
  int64_t triangle;
  ivec3 lo, hi;  // inclusive voxel range
};

struct Sink {
  VoxelGridView exact, grown, shrunk;
  bool with_band;
};

void refine(const ExactTriangle& t, ivec3 lo, ivec3 hi, const Sink& sink) {
  const double grow = sink.with_band ? kBorderlineBand : 0.0;
  const dvec3 center = 0.5 * (dvec3(lo) + dvec3(hi + 1));
  const dvec3 half = 0.5 * dvec3(hi + 1 - lo);
  if (!triangle_box_overlap(t.v0, t.v1, t.v2, t.normal, t.use_normal, center,
                            half + grow + kPruneSlack))
    return;
  if (lo == hi) {
    if (!sink.with_band) {
      if (triangle_box_overlap(t.v0, t.v1, t.v2, t.normal, t.use_normal, center, half))
        sink.exact.set(lo.x, lo.y, lo.z);
      return;
    }
    if (!triangle_box_overlap(t.v0, t.v1, t.v2, t.normal, t.use_normal, center, half + grow))
      return;
    sink.grown.set(lo.x, lo.y, lo.z);
    if (!triangle_box_overlap(t.v0, t.v1, t.v2, t.normal, t.use_normal, center, half)) return;
    sink.exact.set(lo.x, lo.y, lo.z);
    if (triangle_box_overlap(t.v0, t.v1, t.v2, t.normal, t.use_normal, center, half - grow))
      sink.shrunk.set(lo.x, lo.y, lo.z);
    return;
  }
  const ivec3 size = hi - lo;
  const int axis = size.x >= size.y && size.x >= size.z ? 0 : (size.y >= size.z ? 1 : 2);
  const int mid = lo[axis] + size[axis] / 2;
  ivec3 first_hi = hi, second_lo = lo;
  first_hi[axis] = mid;
  second_lo[axis] = mid + 1;
  refine(t, lo, first_hi, sink);
  refine(t, second_lo, hi, sink);
}

}  // namespace

bool triangle_box_overlap(const dvec3& v0, const dvec3& v1, const dvec3& v2, const dvec3& normal,
                          bool use_normal, const dvec3& center, const dvec3& half) {
  const dvec3 a0 = v0 - center, a1 = v1 - center, a2 = v2 - center;
  for (int k = 0; k < 3; ++k) {
    if (std::min({a0[k], a1[k], a2[k]}) > half[k]) return false;
    if (std::max({a0[k], a1[k], a2[k]}) < -half[k]) return false;
  }
  if (use_normal) {
    const double d = glm::dot(normal, a0);
    const double r =
        half.x * std::abs(normal.x) + half.y * std::abs(normal.y) + half.z * std::abs(normal.z);
    if (std::abs(d) > r) return false;
  }
  const dvec3 edges[3] = {a1 - a0, a2 - a1, a0 - a2};
  for (const dvec3& f : edges) {
    if (separated_on(dvec3(0.0, -f.z, f.y), a0, a1, a2, half)) return false;  // x x f
    if (separated_on(dvec3(f.z, 0.0, -f.x), a0, a1, a2, half)) return false;  // y x f
    if (separated_on(dvec3(-f.y, f.x, 0.0), a0, a1, a2, half)) return false;  // z x f
  }
  return true;
}

ExactVoxelization voxelize_exact(const TriangleSoup& soup, const GridSpec& spec, bool with_band) {
  const auto start = std::chrono::steady_clock::now();
  validate_grid_spec(spec, "exact voxelizer");
  require_affine_grid(spec, "exact voxelizer");
  ExactVoxelization out;
  out.exact = VoxelGrid(spec, Memory::host);
  if (with_band) {
    out.grown = VoxelGrid(spec, Memory::host);
    out.shrunk = VoxelGrid(spec, Memory::host);
  }
  const GridTransform to_grid = grid_transform(spec);
  const double grow = with_band ? kBorderlineBand : 0.0;

  std::vector<ExactTriangle> triangles(size_t(soup.triangle_count()));
  std::vector<Block> blocks;
  for (int64_t t = 0; t < soup.triangle_count(); ++t) {
    ExactTriangle& tri = triangles[size_t(t)];
    tri.v0 = to_grid.apply(soup.corners[size_t(3 * t)]);
    tri.v1 = to_grid.apply(soup.corners[size_t(3 * t + 1)]);
    tri.v2 = to_grid.apply(soup.corners[size_t(3 * t + 2)]);
    if (!is_finite_point(tri.v0) || !is_finite_point(tri.v1) || !is_finite_point(tri.v2)) continue;
    tri.normal = triangle_normal(tri.v0, tri.v1, tri.v2);
    tri.use_normal = !is_degenerate_triangle(tri.v0, tri.v1, tri.v2, tri.normal);
    VoxelRange range[3];
    bool empty = false;
    for (int a = 0; a < 3; ++a) {
      range[a] = voxel_range(std::min({tri.v0[a], tri.v1[a], tri.v2[a]}),
                             std::max({tri.v0[a], tri.v1[a], tri.v2[a]}), spec.res[a], grow);
      empty = empty || range[a].empty();
    }
    if (empty) continue;
    for (int z = range[2].first; z <= range[2].last; z += kBlockSide)
      for (int y = range[1].first; y <= range[1].last; y += kBlockSide)
        for (int x = range[0].first; x <= range[0].last; x += kBlockSide) {
          const ivec3 lo(x, y, z);
          const ivec3 hi(std::min(x + kBlockSide - 1, range[0].last),
                         std::min(y + kBlockSide - 1, range[1].last),
                         std::min(z + kBlockSide - 1, range[2].last));
          blocks.push_back({t, lo, hi});
        }
  }

  const Sink sink{out.exact.view(), with_band ? out.grown.view() : VoxelGridView{},
                  with_band ? out.shrunk.view() : VoxelGridView{}, with_band};
  cpu_parallel_for(
      int64_t(blocks.size()),
      [&](int64_t i) {
        const Block& b = blocks[size_t(i)];
        refine(triangles[size_t(b.triangle)], b.lo, b.hi, sink);
      },
      1);
  out.milliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return out;
}

namespace {

VoxelizeResult voxelize_exact_result(Backend backend, const TriangleSoup& soup,
                                     const GridSpec& spec) {
  if (backend != Backend::cpu)
    throw InputError("voxelizer 'exact'", "runs on the CPU only (use --backend cpu)");
  ExactVoxelization exact = voxelize_exact(soup, spec, false);
  VoxelizeResult result;
  result.grid = std::move(exact.exact);
  result.passes.push_back({"voxelize", exact.milliseconds});
  result.counters["triangles"] = soup.triangle_count();
  return result;
}

}  // namespace

void register_exact_voxelizer(Registry<Voxelizer>& registry) {
  registry.add("exact",
               "CPU reference: voxels whose closed box overlaps a triangle (13-axis "
               "separating-axis test, double precision)",
               {}, [](const StrategyParams&) {
                 return std::make_unique<FunctionVoxelizer>("exact", voxelize_exact_result, false);
               });
}

}  // namespace dv
