// Layers-per-texel heatmap (see layer_heatmap.h): a grid of labelled faces, then a colour bar,
// then the labels of its ends.
#include "render/io/layer_heatmap.h"

#include <algorithm>
#include <cmath>
#include <string>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#include <stb_easy_font.h>
#pragma GCC diagnostic pop

namespace dv {

namespace {

// Viridis at 0, 1/4, 1/2, 3/4 and 1 (sRGB).
const dvec3 kViridis[5] = {{0.267, 0.005, 0.329},
                           {0.229, 0.322, 0.546},
                           {0.128, 0.567, 0.551},
                           {0.369, 0.789, 0.383},
                           {0.993, 0.906, 0.144}};

constexpr int kTextHeight = 8;  // stb_easy_font's capitals and digits, in font pixels

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

// Width of `text` in image pixels at font pixel size `s`.
int text_width(const std::string& text, int s) {
  return stb_easy_font_width(const_cast<char*>(text.c_str())) * s;
}

// Draws `text` in white with font pixel size `s`, top-left corner at (x, y): the font's quads
// are axis-aligned whole font pixels.
void draw_text(Image& img, const std::string& text, int x, int y, int s) {
  struct Vertex {
    float x, y, z;
    unsigned char colour[4];
  };
  std::vector<Vertex> quads(text.size() * 4 * 32);
  const int count = stb_easy_font_print(0.0f, 0.0f, const_cast<char*>(text.c_str()), nullptr,
                                        quads.data(), int(quads.size() * sizeof(Vertex)));
  for (int q = 0; q < count; ++q) {
    const Vertex& a = quads[size_t(q) * 4];
    const Vertex& c = quads[size_t(q) * 4 + 2];
    for (int py = int(a.y) * s; py < int(c.y) * s; ++py)
      for (int px = int(a.x) * s; px < int(c.x) * s; ++px) put(img, x + px, y + py, dvec3(1.0));
  }
}

}  // namespace

Image layer_heatmap(const std::vector<int32_t>& layers, int faces, int res,
                    const std::vector<std::string>& labels) {
  const int gap = std::max(1, res / 32), s = std::max(1, res / 64);
  const int bar = std::max(4, res / 16);
  int cell = res;
  for (const std::string& l : labels) cell = std::max(cell, text_width(l, s));
  const int label_band = labels.empty() ? 0 : (kTextHeight + 1) * s;
  const int fit = std::max(1, (kHeatmapMaxWidth + gap) / (cell + gap));
  const int columns = std::clamp(int(std::ceil(std::sqrt(double(faces)))), 1, fit);
  const int rows = std::max(1, (faces + columns - 1) / columns);
  const int row_height = label_band + res + gap;
  const int width = columns * cell + (columns - 1) * gap;
  const int grid_height = rows * row_height;
  Image img(width, grid_height + bar + s + kTextHeight * s + s);
  int32_t max_layers = 1;
  for (int32_t n : layers) max_layers = std::max(max_layers, n);
  for (int f = 0; f < faces; ++f) {
    const int x0 = (f % columns) * (cell + gap), y0 = (f / columns) * row_height;
    if (!labels.empty()) draw_text(img, labels[size_t(f)], x0, y0, s);
    for (int y = 0; y < res; ++y)
      for (int x = 0; x < res; ++x) {
        const int32_t n = layers[(size_t(f) * res + y) * res + x];
        if (n > 0) put(img, x0 + x, y0 + label_band + y, viridis(double(n) / max_layers));
      }
  }
  for (int x = 0; x < width; ++x)
    for (int y = grid_height; y < grid_height + bar; ++y)
      put(img, x, y, viridis(double(x) / std::max(1, width - 1)));
  const int text_y = grid_height + bar + s;
  draw_text(img, "0", 0, text_y, s);
  const std::string top = std::to_string(max_layers);
  draw_text(img, top, width - text_width(top, s), text_y, s);
  return img;
}

}  // namespace dv
