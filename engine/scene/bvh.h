// Bounding-volume hierarchy over world-space triangles, built on the host with binned SAH and
// traversed by shared host/device code (oracle rays, reference render). Nodes are stored
// depth-first: an inner node's left child follows it, `first` holds the right child; a leaf
// covers triangles [first, first + count) of the BVH-ordered triangle array.
#pragma once

#include <cstdint>
#include <vector>

#include "core/math.h"

namespace dv {

struct BvhNode {
  Aabb box;
  int32_t first = 0;
  int32_t count = 0;  // > 0: leaf
};

// Deepest tree the traversal stack supports; the builder guarantees it.
inline constexpr int kBvhMaxDepth = 60;

struct BvhBuild {
  std::vector<BvhNode> nodes;
  std::vector<uint32_t> order;  // order[i] = input triangle stored at BVH position i
  int depth = 0;
};

// Builds over triangle boxes; degenerate (zero-area) triangles are kept.
BvhBuild build_bvh(const std::vector<Aabb>& triangle_boxes, int max_leaf_size = 4);

}  // namespace dv
