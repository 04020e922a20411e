// The sRGB thresholds of the display encoding, and an image's bytes through them (see
// display_encoding.h).
#include "render/io/display_encoding.h"

#include <bit>
#include <cmath>
#include <cstdint>

#include "core/parallel.h"
#include "render/io/image.h"

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

std::vector<unsigned char> srgb_bytes(const Image& image, const DisplayTransform& display) {
  const DisplayEncoding encoding = make_display_encoding(display);
  std::vector<unsigned char> bytes(image.rgb.size());
  cpu_parallel_for_chunks(int64_t(bytes.size()), int64_t(1) << 16, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) bytes[size_t(i)] = encoding.byte(image.rgb[size_t(i)]);
  });
  return bytes;
}

}  // namespace dv
