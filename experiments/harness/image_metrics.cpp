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

// Adds the squared differences of a pixel's three 8-bit channels, in [0, 1] units, to `sum`
// one by one (so image_error's sum keeps its order of additions).
void add_squared_difference(const Image& a, const Image& b, size_t pixel, double& sum) {
  for (size_t i = pixel * 3; i < pixel * 3 + 3; ++i) {
    const double d = (int(srgb_byte(a.rgb[i])) - int(srgb_byte(b.rgb[i]))) / 255.0;
    sum += d * d;
  }
}

// Per pixel the Sobel gradient magnitude of the 8-bit sRGB luminance (Rec. 709 weights on the
// encoded values in [0, 1]), divided by 4: a unit step between two pixel columns reads 1. The
// border repeats its pixels.
std::vector<double> edge_strength(const Image& image) {
  const int w = image.width, h = image.height;
  std::vector<double> luma(size_t(w) * h);
  for (size_t p = 0; p < luma.size(); ++p)
    luma[p] = (0.2126 * srgb_byte(image.rgb[p * 3]) + 0.7152 * srgb_byte(image.rgb[p * 3 + 1]) +
               0.0722 * srgb_byte(image.rgb[p * 3 + 2])) /
              255.0;
  const auto at = [&](int x, int y) {
    return luma[size_t(std::clamp(y, 0, h - 1)) * w + size_t(std::clamp(x, 0, w - 1))];
  };
  std::vector<double> strength(luma.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double gx = (at(x + 1, y - 1) + 2.0 * at(x + 1, y) + at(x + 1, y + 1)) -
                        (at(x - 1, y - 1) + 2.0 * at(x - 1, y) + at(x - 1, y + 1));
      const double gy = (at(x - 1, y + 1) + 2.0 * at(x, y + 1) + at(x + 1, y + 1)) -
                        (at(x - 1, y - 1) + 2.0 * at(x, y - 1) + at(x + 1, y - 1));
      strength[size_t(y) * w + x] = std::sqrt(gx * gx + gy * gy) / 4.0;
    }
  return strength;
}

double edge_error(const Image& image, const Image& reference) {
  const size_t pixels = size_t(image.width) * image.height;
  if (pixels == 0) return 0.0;
  const std::vector<double> a = edge_strength(image), b = edge_strength(reference);
  double sum = 0.0;
  for (size_t p = 0; p < pixels; ++p)
    sum += std::min(1.0, std::max(largest_channel_difference(image, reference, p) / 255.0,
                                  std::abs(a[p] - b[p])));
  return sum / double(pixels);
}

}  // namespace

ImageError image_error(const Image& image, const Image& reference) {
  check_sizes(image, reference);
  const size_t pixels = size_t(image.width) * image.height;
  double sum = 0.0;
  size_t over = 0;
  for (size_t p = 0; p < pixels; ++p) add_squared_difference(image, reference, p, sum);
  for (size_t p = 0; p < pixels; ++p) over += largest_channel_difference(image, reference, p) > 8;
  ImageError e;
  e.rmse = pixels ? std::sqrt(sum / double(pixels * 3)) : 0.0;
  e.psnr_db =
      e.rmse > 0.0 ? 20.0 * std::log10(1.0 / e.rmse) : std::numeric_limits<double>::infinity();
  e.fraction_over_8 = pixels ? double(over) / double(pixels) : 0.0;
  e.edge_error = edge_error(image, reference);
  return e;
}

std::vector<double> view_depths(const VisibleSurface& view, const Camera& camera) {
  const dvec3 forward = glm::normalize(camera.target - camera.position);
  std::vector<double> depth(view.hit.size(), std::numeric_limits<double>::infinity());
  for (size_t p = 0; p < depth.size(); ++p)
    if (view.hit[p]) depth[p] = glm::dot(view.points[p] - camera.position, forward);
  return depth;
}

DepthBins depth_bins(const std::vector<double>& depth, int count) {
  if (count < 1) throw InputError("depth bins", "need at least one bin");
  std::vector<size_t> order;
  for (size_t p = 0; p < depth.size(); ++p)
    if (std::isfinite(depth[p])) order.push_back(p);
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return depth[a] < depth[b]; });
  DepthBins bins;
  bins.bin.assign(depth.size(), count - 1);
  bins.pixels.assign(size_t(count), 0);
  const double inf = std::numeric_limits<double>::infinity();
  bins.edges.assign(size_t(count) + 1, inf);
  const size_t n = order.size(), base = n / size_t(count), longer = n % size_t(count);
  size_t next = 0;
  for (size_t k = 0; k < size_t(count); ++k) {
    const size_t size = base + (k < longer ? 1 : 0);
    if (size > 0) bins.edges[k] = depth[order[next]];
    for (size_t i = 0; i < size; ++i) bins.bin[order[next++]] = int(k);
  }
  if (n > 0) bins.edges.back() = depth[order.back()];
  for (size_t k = size_t(count); k-- > 0;)  // an empty bin starts where the next one does
    if (bins.edges[k] == inf) bins.edges[k] = bins.edges[k + 1];
  for (int b : bins.bin) ++bins.pixels[size_t(b)];
  return bins;
}

std::vector<double> binned_rmse(const Image& image, const Image& reference, const DepthBins& bins) {
  check_sizes(image, reference);
  if (bins.bin.size() != size_t(image.width) * image.height)
    throw InputError("depth bins", "one bin per pixel needed");
  std::vector<double> sum(bins.pixels.size(), 0.0);
  for (size_t p = 0; p < bins.bin.size(); ++p)
    add_squared_difference(image, reference, p, sum[size_t(bins.bin[p])]);
  for (size_t k = 0; k < sum.size(); ++k)
    sum[k] = bins.pixels[k] ? std::sqrt(sum[k] / double(bins.pixels[k] * 3)) : 0.0;
  return sum;
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
