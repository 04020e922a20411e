// The error of advise and --error-budget where shadows cover little of the view:
// experiments/scenes/small-shadows.json, two 0.8-wide squares 4 above a big floor under a spot
// light at height 10 (one opaque, one of alpha 0.5), seen by a wide camera. Their shadows on
// the floor are the squares projected from the light, where the exact transmittance is 0 and
// 0.5 (computed here, and checked against the oracle). The probe strata find them (the light's
// view where the camera's pixels are too few), the old camera-visible p95 is blind to them, and
// the choice of auto --error-budget meets E at uniform points inside each shadow for E = 0.005,
// 0.02 and 0.05, and advise never picks what misses it there, on the CPU and on CUDA (skipped
// without a GPU).
// Also the front per stratum and the image edge error.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <random>

#include "apps/common/error_budget.h"
#include "experiments/advise/advise.h"
#include "experiments/advise/advise_report.h"
#include "experiments/harness/error_summary.h"
#include "experiments/harness/image_metrics.h"
#include "experiments/harness/scene_cache.h"
#include "experiments/source_paths.h"
#include "strategies/shadow/probe.h"
#include "strategies/shadow/shadow_method.h"
#include "tests/support/backends.h"

namespace dv {
namespace {

const dvec3 kLight{0.0, 10.0, 0.5};
constexpr double kSide = 0.8;  // the squares' side

struct Square {
  dvec3 centre;
  double exact;  // T behind it: 1 - alpha
};
constexpr std::array<Square, 2> kSquares{{{{-0.7, 4.0, 0.0}, 0.0}, {{0.7, 4.0, 0.0}, 0.5}}};

std::string scene_path() {
  return test::source_dir() + "/experiments/scenes/small-shadows.json";
}

// The square's shadow on the floor (y = 0): the square projected from the light, a square
// `shadow_side(s)` wide about `shadow_centre(s)`.
double magnification(const Square& s) {
  return kLight.y / (kLight.y - s.centre.y);
}
dvec3 shadow_centre(const Square& s) {
  return kLight + (s.centre - kLight) * magnification(s);
}
double shadow_side(const Square& s) {
  return kSide * magnification(s);
}
bool in_shadow(const Square& s, const dvec3& p) {
  const dvec3 c = shadow_centre(s);
  const double h = 0.5 * shadow_side(s);
  return std::abs(p.y) < 1e-9 && std::abs(p.x - c.x) <= h && std::abs(p.z - c.z) <= h;
}

// `n` uniform points of the square's shadow.
std::vector<dvec3> shadow_points(const Square& s, int n, uint64_t seed) {
  std::mt19937_64 rng(seed);
  const auto uniform = [&] { return double(rng() >> 11) * 0x1.0p-53 - 0.5; };
  const dvec3 c = shadow_centre(s);
  std::vector<dvec3> points;
  for (int i = 0; i < n; ++i)
    points.push_back({c.x + uniform() * shadow_side(s), 0.0, c.z + uniform() * shadow_side(s)});
  return points;
}

constexpr int kShadowPoints = 400;
constexpr uint64_t kShadowSeed = 4242;

// Per square the p95 of |T' - T| of `config` at kShadowPoints uniform points of its shadow.
std::array<double, 2> shadow_p95(SceneCache& cache, const ShadowConfig& config,
                                 const Camera& camera) {
  std::unique_ptr<ShadowMethod> method =
      shadow_registry().create(config.name, StrategyParams(config.params));
  std::array<double, 2> out{};
  for (size_t k = 0; k < kSquares.size(); ++k) {
    const std::vector<dvec3> points = shadow_points(kSquares[k], kShadowPoints, kShadowSeed + k);
    const ProbeResults r =
        probe_transmittance(cache.backend(), cache.data(scene_path()), *method, points, &camera);
    std::vector<double> errors;
    for (double t : r.transmittance) errors.push_back(std::abs(t - kSquares[k].exact));
    out[k] = summarize_errors(errors).p95;
  }
  return out;
}

// The camera at the measurements' size.
Camera camera_at(SceneCache& cache, int width, int height) {
  Camera c = cache.scene(scene_path()).camera;
  c.width = width;
  c.height = height;
  return c;
}

constexpr int kWidth = 64, kHeight = 48;

// The analytic answer is the oracle's; the shadows cover under 5 % of the view; the strata hold
// them (from the light's view: the camera's 64 x 48 pixels see too few), each sample in the
// stratum its shadow says; and where the camera's points alone see no error of a coarse map,
// the strata see a large one.
TEST(AdviseStrata, StrataFindSmallShadowsTheCameraPointsMiss) {
  SceneCache cache(Backend::cpu);
  const std::unique_ptr<ShadowMethod> oracle = shadow_registry().create("reference");
  for (const Square& s : kSquares) {
    const ProbeResults r = probe_transmittance(Backend::cpu, cache.data(scene_path()), *oracle,
                                               shadow_points(s, 50, 7));
    for (double t : r.transmittance) EXPECT_NEAR(t, s.exact, 1e-12);
  }
  const CameraSight& sight = cache.sight(scene_path(), 160, 120);
  size_t seen = 0, shadowed = 0;
  for (size_t i = 0; i < sight.surface.hit.size(); ++i) {
    if (!sight.surface.hit[i]) continue;
    ++seen;
    for (const Square& s : kSquares) shadowed += in_shadow(s, sight.surface.points[i]);
  }
  EXPECT_GT(shadowed, 0u);
  EXPECT_LT(double(shadowed), 0.05 * double(seen)) << shadowed << " of " << seen;

  const StrataSettings settings{500, 200, 1};
  const StratifiedProbes& probes = cache.stratified_probes(scene_path(), kWidth, kHeight, settings);
  for (Stratum s : {Stratum::lit, Stratum::umbra, Stratum::partial}) {
    EXPECT_GE(probes.count(s), settings.stratum_min)
        << to_string(s) << ": " << probes.counts_text();
    EXPECT_FALSE(probes.few(s)) << to_string(s);
  }
  EXPECT_EQ(probes.count(Stratum::media), 0);
  EXPECT_LT(probes.from_camera[size_t(Stratum::umbra)], settings.stratum_min)
      << "the camera saw enough umbra: the light's view was not tested";
  for (const StratumSample& sample : probes.samples) {
    const dvec3& p = probes.points[sample.point];
    const Stratum expected = in_shadow(kSquares[0], p) ? Stratum::umbra
                             : in_shadow(kSquares[1], p)
                                 ? Stratum::partial
                                 : surface_stratum(probes.exact[sample.point]);
    EXPECT_EQ(sample.stratum, expected) << p.x << " " << p.y << " " << p.z;
    if (sample.stratum != Stratum::lit) {
      EXPECT_TRUE(in_shadow(kSquares[0], p) || in_shadow(kSquares[1], p))
          << "a shadow sample outside the shadows: " << p.x << " " << p.z;
    }
  }

  // A coarse map: the old metric (p95 over the camera-visible points alone) reads 0, the
  // strata see its error in the shadows.
  const ShadowConfig coarse{"dsm", {{"res", "32"}, {"storage", "beer"}}};
  const Camera camera = camera_at(cache, kWidth, kHeight);
  const ProbeSet& visible = cache.visible_probes(scene_path(), kWidth, kHeight, 500, 1);
  const std::unique_ptr<ShadowMethod> method =
      shadow_registry().create(coarse.name, StrategyParams(coarse.params));
  const ProbeResults r = probe_transmittance(Backend::cpu, cache.data(scene_path()), *method,
                                             visible.points.points, &camera);
  std::vector<double> camera_errors;
  for (size_t i = 0; i < r.transmittance.size(); ++i)
    camera_errors.push_back(std::abs(r.transmittance[i] - visible.exact[i]));
  EXPECT_LT(summarize_errors(camera_errors).p95, 1e-9);
  AdviseSettings coarse_settings;
  coarse_settings.width = kWidth;
  coarse_settings.height = kHeight;
  coarse_settings.probes = settings.camera_points;
  coarse_settings.repeat = 1;
  AdviseMeasurer measurer(cache, scene_path(), coarse_settings);
  const AdviseMeasurement m = measurer.measure(coarse);
  ASSERT_TRUE(m.ok) << m.failure;
  EXPECT_GT(m.error_p95, 0.05);
  EXPECT_NE(m.worst_stratum(), Stratum::lit);
  EXPECT_TRUE(m.shadows_measured);
}

// The front per stratum keeps, by frame time, each result that lowers that stratum's error; a
// stratum without points has none. advise_report.h's stratum_front.
TEST(AdviseStrata, FrontPerStratum) {
  const auto result = [](double ms, double umbra, int umbra_count, double lit) {
    AdviseResult r;
    r.measurement.ok = true;
    r.measurement.frame_ms = ms;
    r.measurement.strata[size_t(Stratum::umbra)] = {umbra_count, umbra, umbra, false, umbra};
    r.measurement.strata[size_t(Stratum::lit)] = {500, lit, lit, false, lit};
    return r;
  };
  const std::vector<AdviseResult> results{result(3.0, 0.01, 300, 0.0), result(1.0, 0.2, 300, 0.0),
                                          result(2.0, 0.3, 300, 0.0), result(4.0, 0.02, 300, 0.0),
                                          result(5.0, 0.0, 300, 0.0)};
  EXPECT_EQ(stratum_front(results, Stratum::umbra), (std::vector<size_t>{1, 0, 4}));
  EXPECT_EQ(stratum_front(results, Stratum::lit), (std::vector<size_t>{1}));
  EXPECT_TRUE(stratum_front(results, Stratum::partial).empty());
  // A stratum with too few points is judged, and so fronted, by its max.
  StratumError few{20, 0.0, 0.4, true, 0.1};
  EXPECT_EQ(few.judged(), 0.4);
}

// The edge error: 0 for equal images, in (0, 1] for an edge moved by one pixel, and larger for
// deeper stair steps along an edge.
TEST(AdviseStrata, EdgeErrorSeesEdges) {
  const auto edge_image = [](const std::function<bool(int, int)>& bright) {
    Image image(32, 32);
    for (int y = 0; y < 32; ++y)
      for (int x = 0; x < 32; ++x)
        for (int c = 0; c < 3; ++c)
          image.rgb[(size_t(y) * 32 + x) * 3 + c] = bright(x, y) ? 0.8f : 0.1f;
    return image;
  };
  const Image straight = edge_image([](int x, int) { return x >= 16; });
  EXPECT_EQ(image_error(straight, straight).edge_error, 0.0);
  const double moved =
      image_error(edge_image([](int x, int) { return x >= 17; }), straight).edge_error;
  EXPECT_GT(moved, 0.0);
  EXPECT_LE(moved, 1.0);
  const auto stairs = [&](int depth) {
    return image_error(edge_image([=](int x, int y) { return x >= 16 + depth * ((y / 4) % 2); }),
                       straight)
        .edge_error;
  };
  EXPECT_GT(stairs(1), 0.0);
  EXPECT_GT(stairs(2), stairs(1));
  EXPECT_GT(stairs(3), stairs(2));
}

class AdviseStrataOnBackends : public ::testing::TestWithParam<Backend> {
 protected:
  void SetUp() override { DV_SKIP_UNLESS_BACKEND(GetParam()); }
};

// advise picks a configuration that meets E inside the shadows (the camera-visible p95 alone
// passed every one here): at uniform points of both shadows and at its fresh probe points. On
// this scene at 64 x 48 the search seed's p95 can pass maps the fresh points fail; their
// fresh errors then correct the front and the search resumes from it.
TEST_P(AdviseStrataOnBackends, AdviseNeverPicksWhatMissesTheBoundInsideSmallShadows) {
  SceneCache cache(GetParam());
  for (double bound : {0.05, 0.02, 0.005}) {
    AdviseOptions o;
    o.scene = scene_path();
    o.budgets.error = bound;
    o.settings.width = kWidth;
    o.settings.height = kHeight;
    o.settings.probes = 500;
    // Hard shadow edges make the errors 0 or 1: 600 samples per stratum put fewer maps on the
    // wrong side of the p95 by chance than a few hundred.
    o.settings.stratum_min = 600;
    o.settings.repeat = 1;
    o.max_evaluations = 24;
    o.max_res = 1024;
    o.final_rounds = 0;
    const Advice advice = advise(cache, o);
    const StratifiedProbes& fresh =
        cache.stratified_probes(scene_path(), kWidth, kHeight, {500, 600, advice.verify_seed});
    EXPECT_GE(fresh.count(Stratum::umbra), 600);
    EXPECT_GE(fresh.count(Stratum::partial), 600);
    ASSERT_TRUE(advice.pick.has_value()) << "E " << bound << ": no pick\n"
                                         << advice_table(advice, advice.budgets);
    EXPECT_TRUE(advice.verified.shadows_measured);
    const AdviseResult& pick = advice.results[*advice.pick];
    EXPECT_LE(advice.verified.error_p95, bound);
    ASSERT_TRUE(advice.default_index.has_value());
    EXPECT_LE(pick.measurement.image_edge,
              advice.results[*advice.default_index].measurement.image_edge);
    const std::array<double, 2> p95 =
        shadow_p95(cache, pick.config, camera_at(cache, kWidth, kHeight));
    for (size_t k = 0; k < p95.size(); ++k)
      EXPECT_LE(p95[k], bound) << "E " << bound << ", square " << k << ": "
                               << pick.config.param_line();
  }
}

// auto --error-budget's choice meets E inside both shadows.
TEST_P(AdviseStrataOnBackends, ErrorBudgetMeetsTheBoundInsideSmallShadows) {
  SceneCache cache(GetParam());
  for (double bound : {0.05, 0.02, 0.005}) {
    cli::ShadowOptions options;
    options.error_budget = bound;
    cli::resolve_error_budget(options, scene_path(), GetParam());
    ShadowConfig config{"auto", {}};
    for (const std::string& item : options.params) {
      const size_t eq = item.find('=');
      config.params[item.substr(0, eq)] = item.substr(eq + 1);
    }
    std::string why;
    for (const std::string& line : options.budget_explanation) why += line + "\n";
    const std::array<double, 2> p95 = shadow_p95(cache, config, camera_at(cache, 160, 120));
    for (size_t k = 0; k < p95.size(); ++k)
      EXPECT_LE(p95[k], bound) << "E " << bound << ", square " << k << ": " << config.param_line()
                               << "\n"
                               << why;
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, AdviseStrataOnBackends,
                         ::testing::ValuesIn(test::all_backends()),
                         [](const ::testing::TestParamInfo<Backend>& info) {
                           return std::string(to_string(info.param));
                         });

}  // namespace
}  // namespace dv
