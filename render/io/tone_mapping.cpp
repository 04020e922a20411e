// Exposure and tone curves for 8-bit output (see tone_mapping.h).
#include "render/io/tone_mapping.h"

#include <cmath>

#include "core/error.h"

namespace dv {

ToneCurve parse_tone_curve(const std::string& name) {
  if (name == "none") return ToneCurve::none;
  if (name == "reinhard") return ToneCurve::reinhard;
  if (name == "aces") return ToneCurve::aces;
  throw InputError("--tonemap", "unknown tone curve '" + name + "' (known: none, reinhard, aces)");
}

const char* to_string(ToneCurve curve) {
  switch (curve) {
    case ToneCurve::none:
      return "none";
    case ToneCurve::reinhard:
      return "reinhard";
    case ToneCurve::aces:
      return "aces";
  }
  return "?";
}

Image apply_display_transform(const Image& linear, const DisplayTransform& display) {
  if (display.identity()) return linear;
  Image out = linear;
  const double scale = std::exp2(display.exposure_ev);
  for (float& v : out.rgb) v = float(apply_tone_curve(display.curve, double(v) * scale));
  return out;
}

}  // namespace dv
