// Loads of memory that no thread writes while the reading kernel runs (a deep shadow map while
// the camera pass looks it up), through the read-only data path on the device: a global load
// marked non-coherent (ld.global.nc), where a plain dereference through a pointer the compiler
// cannot place compiles to a generic load. Host code dereferences. Host and device code.
#pragma once

#include <cstdint>
#include <cstring>
#include <type_traits>

#include "core/hd.h"

namespace dv {

// *p for an arithmetic T, or a trivially copyable T of 8 or 16 bytes aligned to its size (read
// as one vector load).
template <class T>
DV_HD T read_only(const T* p) {
#if DV_IN_DEVICE_CODE
  if constexpr (std::is_arithmetic_v<T>) {
    return __ldg(p);
  } else {
    static_assert(std::is_trivially_copyable_v<T> && (sizeof(T) == 8 || sizeof(T) == 16) &&
                      alignof(T) == sizeof(T),
                  "read_only: an 8- or 16-byte struct aligned to its size");
    using Bits = std::conditional_t<sizeof(T) == 8, uint2, uint4>;
    const Bits bits = __ldg(reinterpret_cast<const Bits*>(p));
    T out;
    std::memcpy(&out, &bits, sizeof(T));
    return out;
  }
#else
  return *p;
#endif
}

}  // namespace dv
