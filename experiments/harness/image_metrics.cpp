// Image error and difference images (image_metrics.h).
#include "experiments/harness/image_metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

#include <stb_image_write.h>

#include "core/error.h"
#include "experiments/harness/durable_file.h"
#include "render/io/display_encoding.h"
#include "render/io/image.h"
#include "render/io/tone_mapping.h"

namespace dv {

namespace {

void save_png_bytes(const std::string& path, int width, int height,
                    const std::vector<unsigned char>& rgb) {
  std::string png;
  const auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
  };
  if (!stbi_write_png_to_func(append, &png, width, height, 3, rgb.data(), width * 3))
    throw Error(path + ": cannot encode PNG");
  write_file_atomically(path, png);
}

void check_sizes(const Image& a, const Image& b) {
  if (a.width != b.width || a.height != b.height)
    throw InputError("image error", "sizes differ: " + std::to_string(a.width) + "x" +
                                        std::to_string(a.height) + " vs " +
                                        std::to_string(b.width) + "x" + std::to_string(b.height));
}

int largest_channel_difference(const Image& a, const Image& b, size_t pixel) {
  int d = 0;
  for (size_t c = 0; c < 3; ++c)
    d = std::max(
        d, std::abs(int(srgb_byte(a.rgb[pixel * 3 + c])) - int(srgb_byte(b.rgb[pixel * 3 + c]))));
  return d;
}

}  // namespace

ImageError image_error(const Image& image, const Image& reference) {
  check_sizes(image, reference);
  const size_t pixels = size_t(image.width) * image.height;
  double sum = 0.0;
  size_t over = 0;
  for (size_t i = 0; i < pixels * 3; ++i) {
    const double d = (int(srgb_byte(image.rgb[i])) - int(srgb_byte(reference.rgb[i]))) / 255.0;
    sum += d * d;
  }
  for (size_t p = 0; p < pixels; ++p) over += largest_channel_difference(image, reference, p) > 8;
  ImageError e;
  e.rmse = pixels ? std::sqrt(sum / double(pixels * 3)) : 0.0;
  e.psnr_db =
      e.rmse > 0.0 ? 20.0 * std::log10(1.0 / e.rmse) : std::numeric_limits<double>::infinity();
  e.fraction_over_8 = pixels ? double(over) / double(pixels) : 0.0;
  return e;
}

void write_difference_png(const std::string& path, const Image& image, const Image& reference) {
  check_sizes(image, reference);
  const size_t pixels = size_t(image.width) * image.height;
  std::vector<unsigned char> bytes(pixels * 3);
  for (size_t p = 0; p < pixels; ++p) {
    const int d = std::min(255, 4 * largest_channel_difference(image, reference, p));
    bytes[p * 3] = bytes[p * 3 + 1] = bytes[p * 3 + 2] = static_cast<unsigned char>(d);
  }
  save_png_bytes(path, image.width, image.height, bytes);
}

void save_png(const std::string& path, const Image& image) {
  save_png_bytes(path, image.width, image.height, srgb_bytes(image, DisplayTransform{}));
}

}  // namespace dv
