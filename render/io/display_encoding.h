// The display transform and sRGB encoding (exposure, tone curve, then srgb_byte) as host/device
// code: write_png encodes a frame through it, and the viewer's CUDA path turns the renderer's
// device image into the window's bytes on the GPU with it, so both give exactly the same bytes.
// srgb_byte uses pow and lround, which differ between the host and device math libraries; here the
// byte is found instead by comparing the value with 255 thresholds computed once on the host with
// srgb_byte itself (threshold b: the smallest float that srgb_byte maps above b), so the
// device performs no transcendental in this discrete decision. srgb_bytes serves the host
// (PNG files, the viewer's textures).
#pragma once

#include <vector>

#include "core/hd.h"
#include "render/io/tone_mapping.h"

namespace dv {

struct Image;

struct DisplayEncoding {
  double scale = 1.0;  // 2^exposure
  ToneCurve curve = ToneCurve::none;
  bool identity = true;     // DisplayTransform::identity(): the linear value goes straight in
  float thresholds[255]{};  // ascending

  // The byte a PNG of `render` holds for the linear channel value `linear` (not NaN).
  DV_HD unsigned char byte(float linear) const {
    const float v = identity ? linear : float(apply_tone_curve(curve, double(linear) * scale));
    int lo = 0, hi = 255;  // the count of thresholds <= v lies in [lo, hi]
    while (lo < hi) {
      const int mid = (lo + hi) / 2;
      if (thresholds[mid] <= v)
        lo = mid + 1;
      else
        hi = mid;
    }
    return static_cast<unsigned char>(lo);
  }
};

DisplayEncoding make_display_encoding(const DisplayTransform& transform);

// The bytes of `image` shown through `display`, 3 per pixel, rows from the top, as a PNG holds
// them: exactly srgb_byte of the transformed values (not NaN), without a pow per channel, on the
// CPU threads.
std::vector<unsigned char> srgb_bytes(const Image& image, const DisplayTransform& display);

}  // namespace dv
