// Binned-SAH BVH builder (see bvh.h). Deterministic: same input, same tree.
#include "engine/scene/bvh.h"

#include <algorithm>
#include <numeric>

#include "core/error.h"

namespace dv {

namespace {

constexpr int kBins = 16;

double surface_area(const Aabb& b) {
  if (b.empty()) return 0.0;
  dvec3 e = b.hi - b.lo;
  return 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x);
}

struct Builder {
  const std::vector<Aabb>& boxes;
  std::vector<dvec3> centroids;
  std::vector<uint32_t>& order;
  std::vector<BvhNode>& nodes;
  int max_leaf;
  int depth = 0;

  int make_leaf(int node, int begin, int end) {
    nodes[node].first = begin;
    nodes[node].count = end - begin;
    return node;
  }

  // Partitions order[begin, end) and returns the split position, or -1 for a leaf.
  int choose_split(const Aabb& centroid_box, int begin, int end) {
    int axis = 0;
    dvec3 ext = centroid_box.extent();
    if (ext.y > ext[axis]) axis = 1;
    if (ext.z > ext[axis]) axis = 2;
    if (ext[axis] <= 0.0) return -1;
    Aabb bin_box[kBins];
    int bin_count[kBins] = {};
    const double lo = centroid_box.lo[axis], scale = kBins / ext[axis];
    auto bin_of = [&](uint32_t tri) {
      int b = int((centroids[tri][axis] - lo) * scale);
      return std::clamp(b, 0, kBins - 1);
    };
    for (int i = begin; i < end; ++i) {
      int b = bin_of(order[i]);
      bin_box[b].extend(boxes[order[i]]);
      ++bin_count[b];
    }
    double right_area[kBins];
    int right_count[kBins];
    Aabb acc;
    int cnt = 0;
    for (int b = kBins - 1; b > 0; --b) {
      acc.extend(bin_box[b]);
      cnt += bin_count[b];
      right_area[b] = surface_area(acc);
      right_count[b] = cnt;
    }
    double best = 1e300;
    int best_split = -1;
    acc = Aabb{};
    cnt = 0;
    for (int b = 0; b < kBins - 1; ++b) {
      acc.extend(bin_box[b]);
      cnt += bin_count[b];
      if (cnt == 0 || right_count[b + 1] == 0) continue;
      double cost = surface_area(acc) * cnt + right_area[b + 1] * right_count[b + 1];
      if (cost < best) best = cost, best_split = b;
    }
    if (best_split < 0) return -1;
    auto mid = std::partition(order.begin() + begin, order.begin() + end,
                              [&](uint32_t tri) { return bin_of(tri) <= best_split; });
    return int(mid - order.begin());
  }

  int build(int begin, int end, int level) {
    depth = std::max(depth, level);
    int node = int(nodes.size());
    nodes.push_back({});
    Aabb box, centroid_box;
    for (int i = begin; i < end; ++i) {
      box.extend(boxes[order[i]]);
      centroid_box.extend(centroids[order[i]]);
    }
    nodes[node].box = box;
    if (end - begin <= max_leaf) return make_leaf(node, begin, end);
    int split = choose_split(centroid_box, begin, end);
    if (split < 0 || level >= kBvhMaxDepth - 1) {
      if (level >= kBvhMaxDepth - 1 || end - begin <= 64) return make_leaf(node, begin, end);
      split = (begin + end) / 2;  // identical centroids: split by index
    }
    build(begin, split, level + 1);
    int right = build(split, end, level + 1);
    nodes[node].first = right;
    nodes[node].count = 0;
    return node;
  }
};

}  // namespace

BvhBuild build_bvh(const std::vector<Aabb>& triangle_boxes, int max_leaf_size) {
  BvhBuild out;
  const int n = int(triangle_boxes.size());
  if (n == 0) return out;
  out.order.resize(n);
  std::iota(out.order.begin(), out.order.end(), 0u);
  Builder b{triangle_boxes, {}, out.order, out.nodes, max_leaf_size};
  b.centroids.resize(n);
  for (int i = 0; i < n; ++i) b.centroids[i] = triangle_boxes[i].center();
  out.nodes.reserve(size_t(2 * n / std::max(1, max_leaf_size) + 1));
  b.build(0, n, 1);
  out.depth = b.depth;
  if (out.depth > kBvhMaxDepth) throw Error("BVH deeper than the traversal stack");
  return out;
}

}  // namespace dv
