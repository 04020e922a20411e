// Triangle setup and 8x8-tile coverage masks of the tile rasterizer (Knecht 2011 §4.1), written
// once for CPU threads and CUDA kernels: transform to clip space, homogeneous clipping against
// the near plane and the guard band, snapping to 1/256 pixel, and 64-bit integer edge functions
// with the top-left fill rule. The format and the policies are described at the top of
// engine/raster/tile_raster.h; this file is the arithmetic.
#pragma once

#include <cmath>
#include <cstdint>

#include "core/hd.h"
#include "core/math.h"
#include "engine/raster/raster_projection.h"

namespace dv {

inline constexpr int kTileSide = 8;
inline constexpr int kSubpixelBits = 8;
inline constexpr int64_t kSubpixelScale = int64_t(1) << kSubpixelBits;
// Screen positions are kept within this many pixels outside the image (by clipping).
inline constexpr double kGuardBandPixels = double(1 << 19);
// A triangle clipped by the near plane and four guard-band planes: at most 3 + 5 vertices.
inline constexpr int kMaxClipVertices = 8;
inline constexpr int kMaxPiecesPerTriangle = kMaxClipVertices - 2;

// What setup did with a source triangle (bits of setup_triangle's result).
enum RasterSetupFlag : uint32_t {
  kSetupClippedNear = 1u,        // cut by the near plane
  kSetupClippedGuard = 2u,       // cut by the guard band
  kSetupCulledBehind = 4u,       // nothing in front of the near plane
  kSetupCulledOffscreen = 8u,    // no pixel centre of the image inside its bounding box
  kSetupCulledDegenerate = 16u,  // zero area after snapping
  kSetupCulledInvalid = 32u,     // bad index, non-finite coordinates or w <= 0 in front
};
inline constexpr uint32_t kSetupCulledAny =
    kSetupCulledBehind | kSetupCulledOffscreen | kSetupCulledDegenerate | kSetupCulledInvalid;

// One rasterizable triangle (a source triangle, or a piece of a clipped one).
struct RasterTriangle {
  int64_t x[3], y[3];  // snapped pixel coordinates * 256, y down; edge functions > 0 inside
  int32_t tile_x0, tile_y0, tile_x1, tile_y1;  // inclusive tile range; x0 > x1: no tiles
  uint32_t source;                             // index of the source triangle
  uint32_t top_left;  // bit e: edge e (vertex e to vertex e + 1) is a top or a left edge
};

DV_HD inline RasterTriangle empty_raster_triangle(uint32_t source) {
  RasterTriangle t{};
  t.tile_x0 = 1;
  t.tile_x1 = 0;
  t.source = source;
  return t;
}

namespace raster_detail {

struct ClipVertex {
  double x, y, w;
};

DV_HD inline bool finite_number(double v) {
  return v - v == 0.0;
}

// Twice the signed area of (a, b, c) in snapped units; |coordinates| < 2^28 keeps it < 2^59.
DV_HD inline int64_t area2(int64_t ax, int64_t ay, int64_t bx, int64_t by, int64_t cx, int64_t cy) {
  return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
}

DV_HD inline int64_t floor_div(int64_t a, int64_t b) {  // b > 0
  const int64_t q = a / b;
  return (a % b != 0 && a < 0) ? q - 1 : q;
}

// Guard-band plane k of clip space: |x| <= gx * w, |y| <= gy * w.
DV_HD inline double guard_distance(const ClipVertex& v, int plane, double gx, double gy) {
  switch (plane) {
    case 0:
      return gx * v.w - v.x;
    case 1:
      return gx * v.w + v.x;
    case 2:
      return gy * v.w - v.y;
    default:
      return gy * v.w + v.y;
  }
}

// The point where the edge from `in` (d_in >= 0) to `out` (d_out < 0) crosses d = 0. Always
// computed from the inside end, so a shared edge gives bit-identical points in both triangles.
DV_HD inline ClipVertex clip_edge_point(const ClipVertex& in, double d_in, const ClipVertex& out,
                                        double d_out) {
  const double t = d_in / (d_in - d_out);
  return {in.x + t * (out.x - in.x), in.y + t * (out.y - in.y), in.w + t * (out.w - in.w)};
}

// Sutherland-Hodgman step: keeps d >= 0. Returns the vertex count, or -1 if more than
// kMaxClipVertices would result (only possible through rounding on a degenerate polygon).
DV_HD inline int clip_polygon(const ClipVertex* src, const double* d, int n, ClipVertex* dst) {
  int m = 0;
  for (int i = 0; i < n; ++i) {
    const int j = i + 1 == n ? 0 : i + 1;
    const bool in_i = d[i] >= 0.0, in_j = d[j] >= 0.0;
    if (in_i) {
      if (m == kMaxClipVertices) return -1;
      dst[m++] = src[i];
    }
    if (in_i != in_j) {
      if (m == kMaxClipVertices) return -1;
      dst[m++] = in_i ? clip_edge_point(src[i], d[i], src[j], d[j])
                      : clip_edge_point(src[j], d[j], src[i], d[i]);
    }
  }
  return m;
}

// Pixel position * 256, rounded to nearest (ties up) and held inside the guard band.
DV_HD inline bool snap_vertex(const ClipVertex& v, int width, int height, int64_t& x, int64_t& y) {
  if (!(v.w > 0.0)) return false;
  const double sx = (v.x / v.w + 1.0) * (0.5 * double(width)) * double(kSubpixelScale);
  const double sy = (1.0 - v.y / v.w) * (0.5 * double(height)) * double(kSubpixelScale);
  if (!finite_number(sx) || !finite_number(sy)) return false;
  const double lo = -kGuardBandPixels * double(kSubpixelScale);
  const double hi_x = (double(width) + kGuardBandPixels) * double(kSubpixelScale);
  const double hi_y = (double(height) + kGuardBandPixels) * double(kSubpixelScale);
  x = int64_t(floor(clamp_value(sx, lo, hi_x) + 0.5));
  y = int64_t(floor(clamp_value(sy, lo, hi_y) + 0.5));
  return true;
}

// Orients (a, b, c) positively, marks top-left edges and finds the tiles that hold pixel
// centres of its bounding box. Returns false when no pixel centre of the image is in the box.
DV_HD inline bool finish_triangle(const int64_t* xs, const int64_t* ys, int a, int b, int c,
                                  bool flip, int width, int height, RasterTriangle& t) {
  const int order[3] = {a, flip ? c : b, flip ? b : c};
  int64_t min_x = xs[a], max_x = xs[a], min_y = ys[a], max_y = ys[a];
  for (int k = 0; k < 3; ++k) {
    t.x[k] = xs[order[k]];
    t.y[k] = ys[order[k]];
    min_x = min_value(min_x, t.x[k]);
    max_x = max_value(max_x, t.x[k]);
    min_y = min_value(min_y, t.y[k]);
    max_y = max_value(max_y, t.y[k]);
  }
  t.top_left = 0;
  for (int k = 0; k < 3; ++k) {
    const int j = k == 2 ? 0 : k + 1;
    const int64_t dx = t.x[j] - t.x[k], dy = t.y[j] - t.y[k];
    if (dy < 0 || (dy == 0 && dx > 0)) t.top_left |= 1u << k;
  }
  // Pixel p is a candidate when its centre 256 p + 128 lies in [min, max].
  const int64_t half = kSubpixelScale / 2;
  const int64_t px0 = max_value<int64_t>(-floor_div(-(min_x - half), kSubpixelScale), 0);
  const int64_t px1 = min_value<int64_t>(floor_div(max_x - half, kSubpixelScale), width - 1);
  const int64_t py0 = max_value<int64_t>(-floor_div(-(min_y - half), kSubpixelScale), 0);
  const int64_t py1 = min_value<int64_t>(floor_div(max_y - half, kSubpixelScale), height - 1);
  if (px0 > px1 || py0 > py1) return false;
  t.tile_x0 = int32_t(px0 / kTileSide);
  t.tile_x1 = int32_t(px1 / kTileSide);
  t.tile_y0 = int32_t(py0 / kTileSide);
  t.tile_y1 = int32_t(py1 / kTileSide);
  return true;
}

// Clips the polygon in `poly` by the signed distances `d` (>= 0 inside) into `spare`, then the
// two swap roles. False when nothing is left: `n` < 0 for an invalid polygon, else < 3.
DV_HD inline bool clip_and_swap(ClipVertex*& poly, ClipVertex*& spare, const double* d, int& n) {
  n = clip_polygon(poly, d, n, spare);
  if (n < 3) return false;
  ClipVertex* swap = poly;
  poly = spare;
  spare = swap;
  return true;
}

}  // namespace raster_detail

// Sets up source triangle `source` with world-space corners `world`: calls emit(piece) for each
// rasterizable piece (at most kMaxPiecesPerTriangle; one unless it was clipped) and returns
// RasterSetupFlag bits. A culled triangle emits nothing and has exactly one kSetupCulled* bit.
template <class Emit>
DV_HD uint32_t setup_triangle(const RasterProjection& p, const dvec3* world, uint32_t source,
                              Emit&& emit) {
  using namespace raster_detail;
  ClipVertex buffer_a[kMaxClipVertices], buffer_b[kMaxClipVertices];
  double d[kMaxClipVertices];
  ClipVertex* poly = buffer_a;
  ClipVertex* spare = buffer_b;
  int behind = 0;
  for (int k = 0; k < 3; ++k) {
    const dvec4 c = world_to_clip_point(p, world[k]);
    if (!finite_number(c.x) || !finite_number(c.y) || !finite_number(c.z) || !finite_number(c.w))
      return kSetupCulledInvalid;
    poly[k] = {c.x, c.y, c.w};
    d[k] = near_plane_distance(p, c);
    behind += d[k] < 0.0 ? 1 : 0;
  }
  if (behind == 3) return kSetupCulledBehind;
  uint32_t flags = 0;
  int n = 3;
  if (behind > 0) {
    if (!clip_and_swap(poly, spare, d, n)) return n < 0 ? kSetupCulledInvalid : kSetupCulledBehind;
    flags |= kSetupClippedNear;
  }
  const double gx = 1.0 + 2.0 * kGuardBandPixels / double(p.width);
  const double gy = 1.0 + 2.0 * kGuardBandPixels / double(p.height);
  for (int plane = 0; plane < 4; ++plane) {
    int outside = 0;
    for (int k = 0; k < n; ++k) {
      d[k] = guard_distance(poly[k], plane, gx, gy);
      outside += d[k] < 0.0 ? 1 : 0;
    }
    if (outside == 0) continue;
    if (outside == n) return kSetupCulledOffscreen;
    if (!clip_and_swap(poly, spare, d, n))
      return n < 0 ? kSetupCulledInvalid : kSetupCulledOffscreen;
    flags |= kSetupClippedGuard;
  }
  int64_t xs[kMaxClipVertices], ys[kMaxClipVertices];
  for (int k = 0; k < n; ++k)
    if (!snap_vertex(poly[k], p.width, p.height, xs[k], ys[k])) return kSetupCulledInvalid;
  // Fan (0, i, i + 1). In exact arithmetic every piece has the polygon's orientation; a piece
  // that snapping turned over is a sliver thinner than 1/256 px and is dropped.
  int64_t total = 0;
  for (int i = 1; i + 1 < n; ++i) total += area2(xs[0], ys[0], xs[i], ys[i], xs[i + 1], ys[i + 1]);
  if (total == 0) return kSetupCulledDegenerate;
  uint32_t reason = kSetupCulledDegenerate;
  int emitted = 0;
  for (int i = 1; i + 1 < n; ++i) {
    const int64_t area = area2(xs[0], ys[0], xs[i], ys[i], xs[i + 1], ys[i + 1]);
    if (area == 0 || (area > 0) != (total > 0)) continue;
    RasterTriangle t;
    t.source = source;
    if (!finish_triangle(xs, ys, 0, i, i + 1, area < 0, p.width, p.height, t)) {
      reason = kSetupCulledOffscreen;
      continue;
    }
    emit(t);
    ++emitted;
  }
  return emitted > 0 ? flags : reason;
}

// Bits of the tile's pixels that lie inside the image (bit = y * 8 + x within the tile).
DV_HD inline uint64_t tile_valid_mask(int tile_x, int tile_y, int width, int height) {
  const int cols = min_value(kTileSide, width - kTileSide * tile_x);
  const int rows = min_value(kTileSide, height - kTileSide * tile_y);
  if (cols <= 0 || rows <= 0) return 0;
  const uint64_t row_bits = cols >= 8 ? 0xFFull : ((uint64_t(1) << cols) - 1);
  uint64_t mask = 0;
  for (int r = 0; r < rows; ++r) mask |= row_bits << (8 * r);
  return mask;
}

// Pixel centres of tile (tile_x, tile_y) covered by t, restricted to `valid`. A centre on an
// edge is covered only if the edge is a top or a left edge. All values are exact edge-function
// values at pixel centres of the image's tiles: |E| < 2^59, no overflow.
DV_HD inline uint64_t tile_coverage(const RasterTriangle& t, int tile_x, int tile_y,
                                    uint64_t valid) {
  const int64_t step = kSubpixelScale;
  const int64_t cx = int64_t(tile_x) * kTileSide * step + step / 2;
  const int64_t cy = int64_t(tile_y) * kTileSide * step + step / 2;
  int64_t e[3], sx[3], sy[3];
  bool all_inside = true;
  for (int k = 0; k < 3; ++k) {
    const int j = k == 2 ? 0 : k + 1;
    const int64_t dx = t.x[j] - t.x[k], dy = t.y[j] - t.y[k];
    // E(p) = cross(v_j - v_k, p - v_k); covered when E >= 0 (top-left edge) or E >= 1.
    const int64_t bias = ((t.top_left >> k) & 1u) ? 0 : 1;
    e[k] = dx * (cy - t.y[k]) - dy * (cx - t.x[k]) - bias;
    sx[k] = -dy * step;
    sy[k] = dx * step;
    const int64_t span_x = (kTileSide - 1) * sx[k], span_y = (kTileSide - 1) * sy[k];
    const int64_t lo = e[k] + min_value<int64_t>(span_x, 0) + min_value<int64_t>(span_y, 0);
    const int64_t hi = e[k] + max_value<int64_t>(span_x, 0) + max_value<int64_t>(span_y, 0);
    if (hi < 0) return 0;
    if (lo < 0) all_inside = false;
  }
  if (all_inside) return valid;
  uint64_t mask = 0;
  for (int row = 0; row < kTileSide; ++row) {
    int64_t a = e[0], b = e[1], c = e[2];
    for (int col = 0; col < kTileSide; ++col) {
      mask |= uint64_t((a | b | c) >= 0) << (row * kTileSide + col);
      a += sx[0];
      b += sx[1];
      c += sx[2];
    }
    for (int k = 0; k < 3; ++k) e[k] += sy[k];
  }
  return mask & valid;
}

}  // namespace dv
