// Files of linear RGB float images (core/image.h): PNG (sRGB-encoded, 8 bit, through
// stb_image_write, in every build) and OpenEXR (linear half/float, through OpenImageIO, full build
// only).
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/math.h"

namespace dv {

// Writes by extension: .png always; .exr only where exr_supported(). 8-bit files (PNG) show
// `image` through `display` (render/io/tone_mapping.h: exposure and tone curve); EXR stays linear.
struct DisplayTransform;
void write_image(const std::string& path, const Image& image, const DisplayTransform& display);
void write_image(const std::string& path, const Image& image);
// Throws the InputError write_image would throw for this path (type, directory, permission;
// render/io/output_path.h), without writing.
void check_image_path(const std::string& path);
// 8-bit sRGB of the linear image (through render/io/display_encoding.h: exactly srgb_byte per
// channel).
void write_png(const std::string& path, const Image& image);
// 8-bit sRGB bytes, 3 per pixel, rows from the top, as write_png stores them.
void write_png_bytes(const std::string& path, int width, int height,
                     const std::vector<unsigned char>& rgb);
// The 8-bit sRGB value a PNG holds for a linear channel value (clamped to [0, 1]).
inline unsigned char srgb_byte(float linear) {
  const double c = std::clamp(double(linear), 0.0, 1.0);
  const double s = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
  return static_cast<unsigned char>(std::lround(s * 255.0));
}

// Provided by render/io/image_exr_oiio.cpp (full build) or render/io/image_exr_unavailable.cpp
// (lean build).
bool exr_supported();
void write_exr(const std::string& path, const Image& image);

}  // namespace dv
