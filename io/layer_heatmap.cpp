// Layers-per-texel heatmap (see layer_heatmap.h): faces, then a colour bar, then the labels of
// its ends in a 3x5 pixel digit font scaled with the map.
#include "io/layer_heatmap.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace dv {

namespace {

// Viridis at 0, 1/4, 1/2, 3/4 and 1 (sRGB).
const dvec3 kViridis[5] = {{0.267, 0.005, 0.329},
                           {0.229, 0.322, 0.546},
                           {0.128, 0.567, 0.551},
                           {0.369, 0.789, 0.383},
                           {0.993, 0.906, 0.144}};

// 3x5 digits, rows from the top.
const char* const kDigits[10] = {
    "111101101101111", "010110010010111", "111001111100111", "111001111001111", "101101111001001",
    "111100111001111", "111100111101111", "111001001001001", "111101111101111", "111101111001111"};

double srgb_to_linear(double s) {
  return s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4);
}

dvec3 viridis(double t) {
  const double x = std::clamp(t, 0.0, 1.0) * 4.0;
  const int i = std::min(int(x), 3);
  const dvec3 s = kViridis[i] + (kViridis[i + 1] - kViridis[i]) * (x - i);
  return {srgb_to_linear(s.x), srgb_to_linear(s.y), srgb_to_linear(s.z)};
}

void put(Image& img, int x, int y, const dvec3& c) {
  if (x < 0 || y < 0 || x >= img.width || y >= img.height) return;
  float* p = &img.rgb[(size_t(y) * img.width + x) * 3];
  p[0] = float(c.x);
  p[1] = float(c.y);
  p[2] = float(c.z);
}

// Draws the decimal digits of `n` with pixel size `s`, left edge at x (right edge when
// `right_aligned`), top at y.
void draw_number(Image& img, int64_t n, int x, int y, int s, bool right_aligned) {
  const std::string text = std::to_string(n);
  const int width = int(text.size()) * 4 * s - s;
  const int x0 = right_aligned ? x - width : x;
  for (size_t c = 0; c < text.size(); ++c)
    for (int r = 0; r < 5; ++r)
      for (int col = 0; col < 3; ++col)
        if (kDigits[text[c] - '0'][r * 3 + col] == '1')
          for (int dy = 0; dy < s; ++dy)
            for (int dx = 0; dx < s; ++dx)
              put(img, x0 + int(c) * 4 * s + col * s + dx, y + r * s + dy, dvec3(1.0));
}

}  // namespace

Image layer_heatmap(const std::vector<int32_t>& layers, int faces, int res) {
  const int gap = std::max(1, res / 32), s = std::max(1, res / 64);
  const int bar = std::max(4, res / 16);
  const int width = faces * res + (faces - 1) * gap;
  Image img(width, res + gap + bar + s + 5 * s + s);
  int32_t max_layers = 1;
  for (int32_t n : layers) max_layers = std::max(max_layers, n);
  for (int f = 0; f < faces; ++f)
    for (int y = 0; y < res; ++y)
      for (int x = 0; x < res; ++x) {
        const int32_t n = layers[(size_t(f) * res + y) * res + x];
        if (n > 0) put(img, f * (res + gap) + x, y, viridis(double(n) / max_layers));
      }
  for (int x = 0; x < width; ++x)
    for (int y = res + gap; y < res + gap + bar; ++y)
      put(img, x, y, viridis(double(x) / std::max(1, width - 1)));
  draw_number(img, 0, 0, res + gap + bar + s, s, false);
  draw_number(img, max_layers, width, res + gap + bar + s, s, true);
  return img;
}

}  // namespace dv
