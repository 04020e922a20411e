// Image error of a rendered image against the reference render, on the 8-bit sRGB values the
// PNG files hold (what one looks at): RMSE over all channels in [0, 1], PSNR in dB (infinite
// when equal), the fraction of pixels whose largest channel difference exceeds 8/255, and a
// difference image (largest channel difference x4, grey) for the report's image strip. PNGs are
// encoded in memory and written atomically (durable_file.h): a killed run leaves no half file,
// and a full disk is a ResultWriteError that stops the run instead of a silently short file.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/image.h"

namespace dv {

struct ImageError {
  double rmse = 0.0;
  double psnr_db = 0.0;
  double fraction_over_8 = 0.0;
};

// InputError when the sizes differ.
ImageError image_error(const Image& image, const Image& reference);
// Writes the amplified difference as a grey PNG.
void write_difference_png(const std::string& path, const Image& image, const Image& reference);
// Writes the image as write_png does (8-bit sRGB), atomically.
void save_png(const std::string& path, const Image& image);

}  // namespace dv
