// The sRGB thresholds of the display encoding (see display_encoding.h).
#include "io/display_encoding.h"

#include <bit>
#include <cmath>
#include <cstdint>

#include "io/image.h"

namespace dv {

DisplayEncoding make_display_encoding(const DisplayTransform& transform) {
  DisplayEncoding e;
  e.scale = std::exp2(transform.exposure_ev);
  e.curve = transform.curve;
  e.identity = transform.identity();
  // srgb_byte is monotone in its argument, and non-negative floats order like their bit
  // patterns: bisect the patterns in [0, 1] for the first float that encodes above b.
  const uint32_t zero = std::bit_cast<uint32_t>(0.0f), one = std::bit_cast<uint32_t>(1.0f);
  for (int b = 0; b < 255; ++b) {
    uint32_t lo = zero, hi = one;  // srgb_byte(lo) <= b < srgb_byte(hi)
    while (hi - lo > 1) {
      const uint32_t mid = lo + (hi - lo) / 2;
      if (srgb_byte(std::bit_cast<float>(mid)) > b)
        hi = mid;
      else
        lo = mid;
    }
    e.thresholds[b] = std::bit_cast<float>(hi);
  }
  return e;
}

}  // namespace dv
