// Vector math for host and device: GLM types plus the few helpers the shared code needs.
// GLM marks its functions __host__ __device__ when nvcc compiles it (it reads CUDA_VERSION
// from cuda.h, so GLM_FORCE_CUDA must not be defined).
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

#include "core/hd.h"

namespace dv {

using glm::dmat4;
using glm::dvec2;
using glm::dvec3;
using glm::dvec4;
using glm::ivec3;
using glm::u32vec3;
using glm::vec3;

template <class T>
DV_HD constexpr T clamp_value(T v, T lo, T hi) {
  return v < lo ? lo : (v > hi ? hi : v);
}

template <class T>
DV_HD constexpr T min_value(T a, T b) {
  return a < b ? a : b;
}

template <class T>
DV_HD constexpr T max_value(T a, T b) {
  return a > b ? a : b;
}

// Axis-aligned box in double precision. An empty box has min > max.
struct Aabb {
  dvec3 lo{1e300, 1e300, 1e300};
  dvec3 hi{-1e300, -1e300, -1e300};

  DV_HD void extend(const dvec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  DV_HD void extend(const Aabb& b) {
    lo = glm::min(lo, b.lo);
    hi = glm::max(hi, b.hi);
  }
  DV_HD bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
  DV_HD dvec3 extent() const { return empty() ? dvec3(0.0) : hi - lo; }
  DV_HD dvec3 center() const { return 0.5 * (lo + hi); }
  DV_HD bool contains(const dvec3& p) const {
    return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y && p.z >= lo.z && p.z <= hi.z;
  }
};

}  // namespace dv
