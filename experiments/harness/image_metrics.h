// Image error of a rendered image against the reference render, on the 8-bit sRGB values the
// PNG files hold (what one looks at): RMSE over all channels in [0, 1], PSNR in dB (infinite
// when equal), the fraction of pixels whose largest channel difference exceeds 8/255, and a
// difference image (largest channel difference x4, grey) for the report's image strip. PNGs are
// encoded in memory and written atomically (durable_file.h): a killed run leaves no half file,
// and a full disk is a ResultWriteError that stops the run instead of a silently short file.
// The edge error serves where shadow edges matter (a stair-stepped edge changes few pixels by
// much, which RMSE dilutes), with the intent of FLIP (Andersson et al. 2020: colour and feature
// differences, the larger per pixel): per pixel the larger of the largest channel difference
// and the difference of the two images' edge strengths (Sobel gradient magnitude of the 8-bit
// sRGB luminance, divided by 4 so a unit step reads 1), averaged over the image; 0 for equal
// images, at most 1.
// The RMSE also comes binned by view depth (is a method's shadow better near the
// camera, where the image has its large texels?), the depth of the surface each pixel sees.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/image.h"
#include "engine/raster/visible_surface.h"
#include "engine/scene/scene.h"

namespace dv {

struct ImageError {
  double rmse = 0.0;
  double psnr_db = 0.0;
  double fraction_over_8 = 0.0;
  double edge_error = 0.0;
};

// InputError when the sizes differ.
ImageError image_error(const Image& image, const Image& reference);
// The view depth of the surface each pixel of `view` sees (its distance along the camera's
// viewing direction), +infinity where the pixel sees none; `camera` is the one `view` was
// computed for.
std::vector<double> view_depths(const VisibleSurface& view, const Camera& camera);

// Pixels in `count` bins by depth: the pixels that see a surface (finite depth) sorted by depth
// (ties by pixel index) and cut into `count` runs of equal size, nearest first (the first
// size % count bins one pixel longer); the pixels that see no surface (background, or media
// alone) join the last bin, so the bins cover the image.
struct DepthBins {
  std::vector<int> bin;  // per pixel
  std::vector<double>
      edges;  // count + 1: bin k holds the surface depths in [edges[k], edges[k + 1]]
  std::vector<size_t> pixels;  // per bin, background included
};
DepthBins depth_bins(const std::vector<double>& depth, int count);
// The RMSE (as image_error's) over each bin's pixels; 0 for an empty bin.
std::vector<double> binned_rmse(const Image& image, const Image& reference, const DepthBins& bins);

// Writes the amplified difference as a grey PNG.
void write_difference_png(const std::string& path, const Image& image, const Image& reference);
// Writes the image as write_png does (8-bit sRGB), atomically.
void save_png(const std::string& path, const Image& image);

}  // namespace dv
