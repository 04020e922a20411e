// The harness's measurements: probe points (deterministic, on surfaces, isosurfaces or inside
// media as classified, or on the surfaces the camera sees), error summaries with their
// quantiles, and image error against a reference, over the image and per view-depth bin.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <tuple>

#include "core/error.h"
#include "engine/raster/fragment_walk.h"
#include "engine/raster/visible_surface.h"
#include "engine/scene/volume_sampling.h"
#include "experiments/harness/error_summary.h"
#include "experiments/harness/image_metrics.h"
#include "experiments/harness/probe_points.h"
#include "experiments/source_paths.h"
#include "render/frame/raster_render.h"
#include "render/load/mesh_generators.h"
#include "render/load/scene_loader.h"
#include "strategies/shadow/shadow_method.h"
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

// A floor quad (y = 0, 40 wide) filling a 32x24 camera looking straight down from y = 5, and
// a box under it that the camera cannot see.
Scene floor_over_hidden_box() {
  Scene scene;
  scene.meshes = {make_quad(40.0), make_box(dvec3(-1.0, -3.0, -1.0), dvec3(1.0, -1.0, 1.0))};
  Object floor, box;
  floor.name = "floor";
  floor.mesh = 0;
  box.name = "box";
  box.mesh = 1;
  scene.objects = {floor, box};
  scene.lights.push_back(Light{});
  scene.camera.position = dvec3(0.0, 5.0, 0.0);
  scene.camera.target = dvec3(0.0);
  scene.camera.up = dvec3(0.0, 0.0, -1.0);
  scene.camera.width = 32;
  scene.camera.height = 24;
  return scene;
}

TEST(VisibleProbePoints, OnTheSeenSurfaceOnlyAndSeeded) {
  const Scene scene = floor_over_hidden_box();
  const SceneData host(scene, Memory::host);
  const VisibleSurface view = visible_surface(Backend::cpu, host, scene.camera);
  ASSERT_EQ(view.hit.size(), 32u * 24u);
  for (uint8_t h : view.hit) EXPECT_EQ(h, 1);
  const ProbePoints p = make_visible_probe_points(view, 100, 3);
  ASSERT_EQ(p.points.size(), 100u);
  for (size_t i = 0; i < p.points.size(); ++i) {
    EXPECT_EQ(p.classes[i], ProbeClass::visible);
    EXPECT_NEAR(p.points[i].y, 0.0, 1e-9)
        << "probe " << i << " is off the floor (the box is hidden)";
    EXPECT_NE(std::find(view.points.begin(), view.points.end(), p.points[i]), view.points.end());
  }
  std::vector<dvec3> distinct = p.points;
  std::sort(distinct.begin(), distinct.end(), [](const dvec3& a, const dvec3& b) {
    return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z);
  });
  EXPECT_EQ(std::unique(distinct.begin(), distinct.end()), distinct.end()) << "drawn twice";
  EXPECT_EQ(make_visible_probe_points(view, 100, 3).points, p.points);
  EXPECT_NE(make_visible_probe_points(view, 100, 4).points, p.points);
  // More points asked than pixels see a surface: each of them once.
  EXPECT_EQ(make_visible_probe_points(view, 5000, 3).points.size(), 32u * 24u);
  EXPECT_STREQ(to_string(ProbeClass::visible), "visible");
}

TEST(VisibleProbePoints, NoneWhereNoPixelSeesASurface) {
  Scene scene = floor_over_hidden_box();
  scene.camera.target = dvec3(0.0, 10.0, 0.0);  // looking up, away from everything
  scene.camera.up = dvec3(0.0, 0.0, 1.0);
  const SceneData host(scene, Memory::host);
  const VisibleSurface view = visible_surface(Backend::cpu, host, scene.camera);
  EXPECT_TRUE(make_visible_probe_points(view, 50, 1).points.empty());
  const std::vector<double> depth = view_depths(view, scene.camera);
  for (double d : depth) EXPECT_TRUE(std::isinf(d));
  const DepthBins bins = depth_bins(depth, 4);
  EXPECT_EQ(bins.pixels, (std::vector<size_t>{0, 0, 0, 32 * 24}));
}

TEST(ImageMetrics, ViewDepthIsTheDistanceAlongTheViewingDirection) {
  const Scene scene = floor_over_hidden_box();
  const SceneData host(scene, Memory::host);
  const VisibleSurface view = visible_surface(Backend::cpu, host, scene.camera);
  for (double d : view_depths(view, scene.camera)) EXPECT_NEAR(d, 5.0, 1e-9);
}

// The camera's sight lines up with the rendered image: on a scene without media, the pixels
// that see no surface show the background and the others do not.
TEST(ImageMetrics, SightMatchesTheRenderedImage) {
  Scene scene = load_scene(test::source_dir() + "/experiments/scenes/translucent-boxes.json");
  scene.camera.width = 60;
  scene.camera.height = 40;
  const SceneData host(scene, Memory::host);
  const VisibleSurface view = visible_surface(Backend::cpu, host, scene.camera);
  auto oracle = shadow_registry().create("reference");
  const Image image =
      render_raster(Backend::cpu, host, scene.camera, *oracle, scene.background).render.image;
  int seen = 0, background = 0, mismatched = 0;
  for (int y = 0; y < 40; ++y)
    for (int x = 0; x < 60; ++x) {
      const bool shows_background = glm::length(image.at(x, y) - scene.background) < 1e-6;
      const bool hit = view.hit[size_t(y) * 60 + x] != 0;
      (hit ? seen : background)++;
      mismatched += hit == shows_background;
    }
  EXPECT_GT(seen, 100);
  EXPECT_GT(background, 100);
  EXPECT_EQ(mismatched, 0);
}

TEST(ImageMetrics, DepthBinsCoverTheImageNearestFirst) {
  const double inf = std::numeric_limits<double>::infinity();
  // Pixels 0..7 of a 4x2 image; 2 and 6 see no surface.
  const std::vector<double> depth = {5.0, 1.0, inf, 3.0, 2.0, 4.0, inf, 6.0};
  const DepthBins b = depth_bins(depth, 4);
  // Six surface pixels in runs of 2, 2, 1, 1 by depth; the background joins the last bin.
  EXPECT_EQ(b.bin, (std::vector<int>{2, 0, 3, 1, 0, 1, 3, 3}));
  EXPECT_EQ(b.pixels, (std::vector<size_t>{2, 2, 1, 3}));
  EXPECT_EQ(b.edges, (std::vector<double>{1.0, 3.0, 5.0, 6.0, 6.0}));
  // Fewer surface pixels than bins: the empty bins start where the next one does.
  const DepthBins few = depth_bins({2.0, inf, 1.0}, 4);
  EXPECT_EQ(few.bin, (std::vector<int>{1, 3, 0}));
  EXPECT_EQ(few.pixels, (std::vector<size_t>{1, 1, 0, 1}));
  EXPECT_EQ(few.edges, (std::vector<double>{1.0, 2.0, 2.0, 2.0, 2.0}));
  EXPECT_THROW(depth_bins(depth, 0), InputError);

  Image reference(4, 2), image(4, 2);
  image.rgb[1 * 3] = 1.0f;      // pixel 1 (bin 0): one channel 0 -> 255
  image.rgb[6 * 3 + 2] = 1.0f;  // pixel 6 (bin 3, background): one channel 0 -> 255
  const std::vector<double> rmse = binned_rmse(image, reference, b);
  ASSERT_EQ(rmse.size(), 4u);
  EXPECT_NEAR(rmse[0], std::sqrt(1.0 / 6.0), 1e-12);
  EXPECT_EQ(rmse[1], 0.0);
  EXPECT_EQ(rmse[2], 0.0);
  EXPECT_NEAR(rmse[3], std::sqrt(1.0 / 9.0), 1e-12);
  // The bins split the image's squared error: their pixel-weighted mean square is the image's.
  double total = 0.0;
  for (size_t k = 0; k < 4; ++k) total += double(b.pixels[k]) * rmse[k] * rmse[k];
  EXPECT_NEAR(std::sqrt(total / 8.0), image_error(image, reference).rmse, 1e-12);
  EXPECT_THROW(binned_rmse(image, reference, few), InputError);
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
  EXPECT_DOUBLE_EQ(s.p50, 1.00);  // rank 100
  EXPECT_DOUBLE_EQ(s.p90, 1.80);  // rank 180
  EXPECT_DOUBLE_EQ(s.p95, 1.90);  // rank 190
  // Five errors, unsorted: ranks ceil(2.5) = 3, ceil(4.5) = 5, ceil(4.75) = 5.
  const ErrorSummary five = summarize_errors({0.3, 0.1, 0.5, 0.2, 0.4});
  EXPECT_DOUBLE_EQ(five.p50, 0.3);
  EXPECT_DOUBLE_EQ(five.p90, 0.5);
  EXPECT_DOUBLE_EQ(five.p95, 0.5);
  EXPECT_DOUBLE_EQ(five.p99, 0.5);
  // A saturated tail: max and p99 at 1 say nothing the lower quantiles do not tell apart.
  std::vector<double> saturated(100, 0.01);
  for (int i = 0; i < 6; ++i) saturated[size_t(i)] = 1.0;
  const ErrorSummary sat = summarize_errors(saturated);
  EXPECT_EQ(sat.p99, 1.0);
  EXPECT_EQ(sat.p95, 1.0);
  EXPECT_EQ(sat.p90, 0.01);
  EXPECT_DOUBLE_EQ(summarize_errors({0.5}).p99, 0.5);
  EXPECT_EQ(summarize_errors({}).count, 0u);
}

TEST(ErrorSummary, IntervalsOfTheMeanAndTheP95) {
  std::vector<double> errors;
  for (int i = 1; i <= 200; ++i) errors.push_back(i * 0.01);
  const ErrorSummary s = summarize_errors(errors);
  // The sample standard deviation of 0.01, ..., 2.00: 0.01 sqrt(n (n^2 - 1) / 12 / (n - 1)).
  const double sd = 0.01 * std::sqrt(200.0 * (200.0 * 200.0 - 1.0) / 12.0 / 199.0);
  EXPECT_NEAR(s.mean_hi - s.mean, 1.96 * sd / std::sqrt(200.0), 1e-12);
  EXPECT_NEAR(s.mean - s.mean_lo, 1.96 * sd / std::sqrt(200.0), 1e-12);
  // Ranks 190 -+ 1.96 sqrt(9.5) = 183.96 .. 196.04: down to 183, up to 197.
  EXPECT_DOUBLE_EQ(s.p95_lo, 1.83);
  EXPECT_DOUBLE_EQ(s.p95_hi, 1.97);
  const ErrorSummary one = summarize_errors({0.25});
  EXPECT_EQ(one.mean_lo, 0.25);
  EXPECT_EQ(one.mean_hi, 0.25);
  EXPECT_EQ(one.p95_lo, 0.25);
  EXPECT_EQ(one.p95_hi, 0.25);
}

// Over 2,000 errors from a known law (exponential of mean 0.02, p95 = 0.02 ln 20), the two
// intervals hold the true values in 93-97 % of 400 draws.
TEST(ErrorSummary, IntervalsCoverTheTrueMeanAndP95) {
  std::mt19937_64 rng(20261206);
  std::exponential_distribution<double> law(1.0 / 0.02);
  const double true_mean = 0.02, true_p95 = 0.02 * std::log(20.0);
  int mean_inside = 0, p95_inside = 0;
  const int draws = 400;
  for (int d = 0; d < draws; ++d) {
    std::vector<double> errors(2000);
    for (double& e : errors) e = law(rng);
    const ErrorSummary s = summarize_errors(errors);
    mean_inside += s.mean_lo <= true_mean && true_mean <= s.mean_hi;
    p95_inside += s.p95_lo <= true_p95 && true_p95 <= s.p95_hi;
  }
  EXPECT_GE(mean_inside, int(0.93 * draws));
  EXPECT_LE(mean_inside, int(0.97 * draws));
  EXPECT_GE(p95_inside, int(0.93 * draws));
  EXPECT_LE(p95_inside, int(0.97 * draws));
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
