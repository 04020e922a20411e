// A linear RGB float image in memory: what the renderers produce and every writer, metric and
// viewer reads. Files are written by render/io/image.h.
#pragma once

#include <cstddef>
#include <vector>

#include "core/math.h"

namespace dv {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<float> rgb;  // row-major from the top row, 3 floats per pixel, linear

  Image() = default;
  Image(int w, int h) : width(w), height(h), rgb(size_t(w) * h * 3, 0.0f) {}
  dvec3 at(int x, int y) const {
    const float* p = &rgb[(size_t(y) * width + x) * 3];
    return {p[0], p[1], p[2]};
  }
};

}  // namespace dv
