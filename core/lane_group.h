// Lanes of one warp that share a task (the camera pass's volume tiles split each pixel's samples
// between a few lanes): which share this lane takes, and the values of the others. In device code
// a group is `count` consecutive lanes starting at a multiple of `count`; CPU threads have no
// lanes, so there the code that shares a task does every share itself
// (render/frame/shade_payload.h).
#pragma once

#include <cstdint>

#include "core/atomic.h"
#include "core/hd.h"
#include "core/math.h"

namespace dv {

struct LaneGroup {
  int rank = 0;   // this lane's share
  int count = 1;  // lanes in the group, a power of two up to 32
};

#if DV_IN_DEVICE_CODE
__device__ inline unsigned lane_group_mask(const LaneGroup& g) {
  const unsigned ones = g.count >= 32 ? 0xffffffffu : (1u << g.count) - 1u;
  return ones << (warp_lane() / g.count * g.count);
}

// `value` of the group's lane `from` (every lane of the group must call this together).
template <class T>
__device__ T lane_value(const LaneGroup& g, T value, int from) {
  return __shfl_sync(lane_group_mask(g), value, warp_lane() / g.count * g.count + from);
}

__device__ inline dvec3 lane_value(const LaneGroup& g, const dvec3& value, int from) {
  return dvec3(lane_value(g, value.x, from), lane_value(g, value.y, from),
               lane_value(g, value.z, from));
}
#endif

}  // namespace dv
