// FNV-1a 64-bit hashing of plain values: content fingerprints for caches that must notice any
// change in what they were built from (the effect planner's per-object and per-light keys).
// Not cryptographic. Numbers are hashed by their bytes (so -0.0 and 0.0 differ: a rebuild too
// many, never one too few).
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "core/math.h"

namespace dv {

class ContentHash {
 public:
  ContentHash& bytes(const void* data, size_t count) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < count; ++i) value_ = (value_ ^ p[i]) * 0x100000001b3ull;
    return *this;
  }
  template <class T>
  requires std::is_arithmetic_v<T> || std::is_enum_v<T> ContentHash& add(T v) {
    return bytes(&v, sizeof v);
  }
  ContentHash& add(const dvec3& v) { return add(v.x).add(v.y).add(v.z); }
  ContentHash& add(const dmat4& m) {
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) add(m[c][r]);
    return *this;
  }
  uint64_t value() const { return value_; }

 private:
  uint64_t value_ = 0xcbf29ce484222325ull;
};

}  // namespace dv
