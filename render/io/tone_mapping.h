// Exposure and tone curves for 8-bit output: render writes linear radiometric values
// (renderer units, see render/load/gltf_import.h), and a PNG can hold only [0, 1]. The display
// transform scales by 2^EV and maps through a tone curve per channel before sRGB encoding;
// EXR files stay linear and untouched.
#pragma once

#include <string>

#include "core/hd.h"
#include "render/io/image.h"

namespace dv {

enum class ToneCurve { none, reinhard, aces };

// none: clamp at 1 (the encoder's); reinhard: x / (1 + x); aces: Narkowicz's 2015 fit of the
// ACES filmic curve, x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14) clamped to [0, 1]. All
// map 0 to 0 and are monotone on x >= 0; negative inputs give 0. Host and device code (the
// viewer's CUDA display path applies it on the GPU).
DV_HD inline double apply_tone_curve(ToneCurve curve, double x) {
  x = x < 0.0 ? 0.0 : x;
  if (curve == ToneCurve::reinhard) return x / (1.0 + x);
  if (curve == ToneCurve::aces) {
    const double y = x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14);
    return y < 0.0 ? 0.0 : (1.0 < y ? 1.0 : y);
  }
  return x;
}

// The curve render's and view's PNGs go through unless --tonemap says otherwise: aces, which
// keeps shading up to about 5.7 (byte 255 from there; a white model under the staged key light
// reaches about 2), where `none` clips every value above 1 to white.
inline constexpr ToneCurve kDefaultToneCurve = ToneCurve::aces;

ToneCurve parse_tone_curve(const std::string& name);  // none | reinhard | aces
const char* to_string(ToneCurve curve);

struct DisplayTransform {
  double exposure_ev = 0.0;  // linear values are multiplied by 2^exposure_ev
  ToneCurve curve = ToneCurve::none;
  bool identity() const { return exposure_ev == 0.0 && curve == ToneCurve::none; }
};

// The image as an 8-bit file should show it: exposure, then the tone curve, per channel.
Image apply_display_transform(const Image& linear, const DisplayTransform& display);

}  // namespace dv
