// The harness's measurements: probe points (deterministic, on surfaces, isosurfaces or inside
// media as classified), error summaries and image error against a reference.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "engine/raster/fragment_walk.h"
#include "engine/scene/volume_sampling.h"
#include "experiments/harness/error_summary.h"
#include "experiments/harness/image_metrics.h"
#include "experiments/harness/probe_points.h"
#include "experiments/source_paths.h"
#include "render/load/scene_loader.h"
#include "strategies/voxelizer/triangle_soup.h"

namespace dv {
namespace {

// Distance from p to triangle (a, b, c), by projection onto its plane and its edges.
double distance_to_triangle(const dvec3& p, const dvec3& a, const dvec3& b, const dvec3& c) {
  const dvec3 n = glm::normalize(glm::cross(b - a, c - a));
  const dvec3 q = p - n * glm::dot(p - a, n);
  const bool inside = glm::dot(glm::cross(b - a, q - a), n) >= -1e-12 &&
                      glm::dot(glm::cross(c - b, q - b), n) >= -1e-12 &&
                      glm::dot(glm::cross(a - c, q - c), n) >= -1e-12;
  if (inside) return std::abs(glm::dot(p - a, n));
  double best = 1e300;
  for (auto [u, v] : {std::pair{a, b}, {b, c}, {c, a}}) {
    const double t = std::clamp(glm::dot(p - u, v - u) / glm::dot(v - u, v - u), 0.0, 1.0);
    best = std::min(best, glm::length(p - (u + (v - u) * t)));
  }
  return best;
}

TEST(ProbePoints, SeededPointsOnSurfacesAndInsideMedia) {
  const Scene scene = load_scene(test::source_dir() + "/experiments/scenes/demo.json");
  const SceneData host(scene, Memory::host);
  const ProbePoints p = make_probe_points(scene, host, 60, 0.25, 7);
  ASSERT_EQ(p.points.size(), 60u);
  ASSERT_EQ(p.classes.size(), 60u);
  const TriangleSoup soup = triangle_soup(scene);
  int medium = 0;
  for (size_t i = 0; i < p.points.size(); ++i) {
    if (p.classes[i] == ProbeClass::medium) {
      ++medium;
      EXPECT_GT(media_containing(host.view(), p.points[i]).inside.count, 0) << i;
      continue;
    }
    double nearest = 1e300;
    for (int64_t t = 0; t < soup.triangle_count(); ++t) {
      const dvec3* c = &soup.corners[size_t(t) * 3];
      nearest = std::min(nearest, distance_to_triangle(p.points[i], c[0], c[1], c[2]));
    }
    EXPECT_LT(nearest, 1e-9) << "surface point " << i << " is off every triangle";
  }
  EXPECT_EQ(medium, 15);
  const ProbePoints again = make_probe_points(scene, host, 60, 0.25, 7);
  EXPECT_EQ(again.points, p.points);
  EXPECT_NE(make_probe_points(scene, host, 60, 0.25, 8).points, p.points);
}

TEST(ProbePoints, SceneWithoutMediaGivesSurfacePointsOnly) {
  const Scene scene = load_scene(test::source_dir() + "/experiments/scenes/translucent-boxes.json");
  const SceneData host(scene, Memory::host);
  const ProbePoints p = make_probe_points(scene, host, 20, 0.5, 1);
  ASSERT_EQ(p.points.size(), 20u);
  for (ProbeClass c : p.classes) EXPECT_EQ(c, ProbeClass::surface);
}

// Isosurface probes (Hadwiger 2006's isosurface self-shadowing): the CT phantom of the hadwiger
// experiment's smoke form has no visible mesh but its volume; with an isovalue its surface
// probes lie on the volume's isosurface (trilinear density there equals the isovalue), without
// one there are none.
TEST(ProbePoints, IsosurfaceProbesLieOnTheIsosurface) {
  const Scene scene = load_scene(test::source_dir() + "/experiments/scenes/ct-phantom.json");
  const SceneData host(scene, Memory::host);
  const SceneView& view = host.view();
  // Surface probes of `p` where some volume's density is the isovalue.
  const auto on_isosurface = [&](const ProbePoints& p) {
    int count = 0;
    for (size_t i = 0; i < p.points.size(); ++i)
      for (int32_t o = 0; o < int32_t(view.objects.size); ++o) {
        const ObjectView& ov = view.objects[o];
        if (p.classes[i] != ProbeClass::surface || ov.interior != InteriorKind::volume) continue;
        const dvec3 g = world_to_grid(ov, p.points[i]);
        count += std::abs(density_at_grid(view, view.volumes[ov.volume], g) - 0.175) < 1e-6;
      }
    return count;
  };
  const ProbePoints p = make_probe_points(scene, host, 60, 0.5, 3, 0.175);
  ASSERT_EQ(p.points.size(), 60u);
  EXPECT_GT(on_isosurface(p), 5);
  EXPECT_EQ(make_probe_points(scene, host, 60, 0.5, 3, 0.175).points, p.points);
  EXPECT_EQ(on_isosurface(make_probe_points(scene, host, 60, 0.5, 3)), 0);
}

TEST(ErrorSummary, MaxMeanAndNearestRankP99) {
  std::vector<double> errors;
  for (int i = 1; i <= 200; ++i) errors.push_back(i * 0.01);
  const ErrorSummary s = summarize_errors(errors);
  EXPECT_EQ(s.count, 200u);
  EXPECT_DOUBLE_EQ(s.max, 2.0);
  EXPECT_NEAR(s.mean, 1.005, 1e-12);
  EXPECT_DOUBLE_EQ(s.p99, 1.98);  // rank ceil(0.99 * 200) = 198
  EXPECT_DOUBLE_EQ(summarize_errors({0.5}).p99, 0.5);
  EXPECT_EQ(summarize_errors({}).count, 0u);
}

TEST(ImageMetrics, ErrorOnTheEightBitValues) {
  Image reference(4, 2), image(4, 2);
  const ImageError same = image_error(image, reference);
  EXPECT_EQ(same.rmse, 0.0);
  EXPECT_TRUE(std::isinf(same.psnr_db));
  EXPECT_EQ(same.fraction_over_8, 0.0);
  image.rgb[0] = 1.0f;    // one channel of one pixel: 0 -> 255
  image.rgb[4] = 0.002f;  // 0.002 linear is sRGB byte 7: within 8/255
  const ImageError e = image_error(image, reference);
  EXPECT_NEAR(e.rmse, std::sqrt((1.0 + (7.0 / 255) * (7.0 / 255)) / 24.0), 1e-12);
  EXPECT_NEAR(e.psnr_db, 20.0 * std::log10(1.0 / e.rmse), 1e-12);
  EXPECT_EQ(e.fraction_over_8, 1.0 / 8.0);
  EXPECT_THROW(image_error(Image(3, 2), reference), InputError);
}

}  // namespace
}  // namespace dv
