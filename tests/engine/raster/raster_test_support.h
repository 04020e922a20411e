// Shared pieces of the tile-rasterizer tests: a fixture parameterised over backends (CUDA cases
// skip without a GPU, with the reason), triangle soups uploaded to the backend's memory, runs
// that bring lists and per-pixel counts back to the host, and an independent reference:
// projection by camera_rays.h's pixel formula and double-precision point-in-polygon tests with
// an "ambiguous" band of 1/256 pixel around every edge.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <ostream>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "cuda/device_memory.h"
#include "engine/raster/camera_rays.h"
#include "engine/raster/tile_raster.h"
#include "engine/scene/scene.h"

namespace dv {

// Test names and failure messages say "cpu" / "cuda" instead of a byte dump.
inline void PrintTo(Backend backend, std::ostream* out) {
  *out << to_string(backend);
}

}  // namespace dv

namespace dv::test {

inline constexpr double kEdgeTolerance = 1.0 / 256.0;  // pixels

struct Soup {
  std::vector<dvec3> vertices;
  std::vector<u32vec3> triangles;

  void add(const TriangleMesh& mesh, const dmat4& transform = dmat4(1.0)) {
    const uint32_t base = uint32_t(vertices.size());
    for (const dvec3& p : mesh.positions) vertices.push_back(dvec3(transform * dvec4(p, 1.0)));
    for (const u32vec3& t : mesh.triangles) triangles.push_back(t + u32vec3(base));
  }
  void add_triangle(const dvec3& a, const dvec3& b, const dvec3& c) {
    const uint32_t base = uint32_t(vertices.size());
    vertices.insert(vertices.end(), {a, b, c});
    triangles.push_back({base, base + 1, base + 2});
  }
};

struct RasterRun {
  TileLists lists;               // in host memory
  std::vector<uint32_t> counts;  // fragments per pixel, computed on the run's backend
  int width = 0, height = 0;
  uint32_t count(int x, int y) const { return counts[size_t(y) * width + x]; }
};

inline RasterRun rasterize(Backend backend, const Soup& soup, const RasterProjection& projection,
                           const RasterOptions& options = {}) {
  const Memory memory = memory_of(backend);
  const Buffer<dvec3> vertices(memory, std::span<const dvec3>(soup.vertices), "test vertices");
  const Buffer<u32vec3> triangles(memory, std::span<const u32vec3>(soup.triangles),
                                  "test triangles");
  const RasterView view{projection, vertices.const_view(), triangles.const_view()};
  const TileLists lists = rasterize_tiles(backend, view, options);
  RasterRun run;
  run.counts = count_pixel_fragments(backend, lists).to_vector();
  run.lists = lists.to_host();
  run.width = projection.width;
  run.height = projection.height;
  return run;
}

class RasterBackendTest : public ::testing::TestWithParam<Backend> {
 protected:
  void SetUp() override {
    std::string why;
    if (GetParam() == Backend::cuda && !cuda_device_available(&why))
      GTEST_SKIP() << "the CUDA backend needs a GPU: " << why;
  }
  Backend backend() const { return GetParam(); }
};

inline std::string backend_name(const ::testing::TestParamInfo<Backend>& info) {
  return to_string(info.param);
}

inline Camera test_camera(const dvec3& position, const dvec3& target, int width, int height,
                          double near_plane = 0.01) {
  Camera c;
  c.position = position;
  c.target = target;
  c.width = width;
  c.height = height;
  c.near_plane = near_plane;
  return c;
}

// Pixel coordinates (x right, y down) of a world point in front of the camera, from the pixel
// formula of camera_ray_direction, independently of the rasterizer's matrices.
inline dvec2 reference_pixel(const CameraView& c, const dvec3& p) {
  const dvec3 d = p - c.position;
  const double depth = glm::dot(d, c.forward);
  const double sx = glm::dot(d, c.right) / glm::dot(c.right, c.right) / depth;
  const double sy = glm::dot(d, c.up) / glm::dot(c.up, c.up) / depth;
  return {(sx + 1.0) * 0.5 * c.width, (1.0 - sy) * 0.5 * c.height};
}

// The part of a convex world polygon at depth >= near in front of the camera.
inline std::vector<dvec3> clip_to_near(const CameraView& c, const std::vector<dvec3>& polygon) {
  std::vector<dvec3> out;
  const size_t n = polygon.size();
  for (size_t i = 0; i < n; ++i) {
    const dvec3& a = polygon[i];
    const dvec3& b = polygon[(i + 1) % n];
    const double da = glm::dot(a - c.position, c.forward) - c.near_plane;
    const double db = glm::dot(b - c.position, c.forward) - c.near_plane;
    if (da >= 0.0) out.push_back(a);
    if ((da >= 0.0) != (db >= 0.0)) out.push_back(a + (b - a) * (da / (da - db)));
  }
  return out;
}

enum class Side { outside, inside, ambiguous };

// Where point p lies relative to a convex polygon (either orientation), with a band of
// `tolerance` around each edge line counted as ambiguous.
inline Side classify(const std::vector<dvec2>& polygon, const dvec2& p,
                     double tolerance = kEdgeTolerance) {
  const size_t n = polygon.size();
  if (n < 3) return Side::outside;
  double area = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const dvec2 &a = polygon[i], &b = polygon[(i + 1) % n];
    area += a.x * b.y - a.y * b.x;
  }
  if (area == 0.0) return Side::outside;
  const double sign = area > 0.0 ? 1.0 : -1.0;
  double closest = 1e300;
  for (size_t i = 0; i < n; ++i) {
    const dvec2 &a = polygon[i], &b = polygon[(i + 1) % n];
    const dvec2 e = b - a;
    const double length = glm::length(e);
    if (length == 0.0) continue;
    const double distance = sign * (e.x * (p.y - a.y) - e.y * (p.x - a.x)) / length;
    closest = std::min(closest, distance);
  }
  if (closest > tolerance) return Side::inside;
  if (closest < -tolerance) return Side::outside;
  return Side::ambiguous;
}

inline dvec2 pixel_center(int x, int y) {
  return {x + 0.5, y + 0.5};
}

// Reference coverage of a world polygon seen by `camera`: near-clipped, projected.
inline std::vector<dvec2> project_polygon(const CameraView& c, const std::vector<dvec3>& polygon) {
  std::vector<dvec2> out;
  for (const dvec3& p : clip_to_near(c, polygon)) out.push_back(reference_pixel(c, p));
  return out;
}

// The entries of tile t in a host TileLists.
inline std::vector<TileEntry> tile_entries(const TileLists& lists, int64_t t) {
  const TileListsView v = lists.view();
  return std::vector<TileEntry>(v.entries.data + v.offsets[t], v.entries.data + v.offsets[t + 1]);
}

}  // namespace dv::test
