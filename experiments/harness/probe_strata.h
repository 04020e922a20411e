// Probe points stratified by what the exact oracle says about them, so that the error of
// `deepvox advise` and `--shadows auto --error-budget` sees the shadows however little of the
// view they cover. A sample is one (point, light) pair; its stratum: lit (T = 1), umbra
// (T < kUmbraTransmittance), partial (in between: translucent casters, media, edges) for a
// surface point, media for a point inside a medium; a sample outside a spot light's cone (T = 0
// by the cone, not a shadow) is in none, nor is a surface sample whose seen side faces away from
// the light (the renderer's n . l <= 0: its transmittance is never used; where shadow methods
// answer such back faces differently from the oracle, counting them put every method at p95 1). The
// points come, in this order:
//  1. the camera-visible surface points (probe_points.h's `visible` draw, all its samples);
//  2. while a surface stratum (lit, umbra, partial) holds fewer than `stratum_min` samples, more
//     of the pixels the camera sees, in the same uniform draw, keeping only samples of the short
//     strata;
//  3. while a surface stratum still does (the camera sees too little shadow at this size, or too
//     little lit ground inside a narrow spot cone), each light's view of the receivers: a
//     uniform surface point (probe_points.h) and, from each light through it, the nearest
//     surface behind it, each kept where the camera sees it (between the pixel centres of the
//     measuring size: shadows too small for its pixels), again only samples of the short
//     strata;
//  4. with media, as many world-uniform points inside media (probe_points.h) as the first
//     camera draw or the stratum minimum, whichever is more, all their samples.
// Within a stratum, the camera's samples are a uniform draw of its pixels; the light view's are
// added only where the camera has too few. A stratum that still has fewer than `stratum_min`
// samples is `few`: its p95 cannot be estimated, so it is judged by its max (StratumError).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/math.h"
#include "engine/raster/visible_surface.h"
#include "engine/scene/scene.h"
#include "engine/scene/scene_view.h"

namespace dv {

enum class Stratum : uint8_t { lit, umbra, partial, media };
inline constexpr size_t kStrata = 4;
inline constexpr std::array<Stratum, kStrata> kAllStrata{Stratum::lit, Stratum::umbra,
                                                         Stratum::partial, Stratum::media};
const char* to_string(Stratum s);
// Whether the stratum holds shadow (every one but lit).
inline bool is_shadow(Stratum s) {
  return s != Stratum::lit;
}

// Exact transmittance below this is umbra; at or above 1 - kLitTolerance it is lit.
inline constexpr double kUmbraTransmittance = 1e-3;
inline constexpr double kLitTolerance = 1e-9;
// A surface sample's stratum from the oracle's T.
Stratum surface_stratum(double exact);

enum class ProbeSource : uint8_t { camera, light_view, medium };

struct StrataSettings {
  int camera_points = 2000;  // the first camera-visible draw
  int stratum_min = 200;  // samples wanted per surface stratum (a p95 from 200: the 10th largest)
  uint64_t seed = 1;
};

struct StratumSample {
  uint32_t point = 0;
  uint16_t light = 0;
  Stratum stratum = Stratum::lit;
};

struct StratifiedProbes {
  std::vector<dvec3> points;
  std::vector<ProbeSource> sources;  // per point
  int light_count = 0;
  std::vector<double> exact;  // [point * light_count + light], the oracle
  std::vector<StratumSample> samples;
  std::array<int, kStrata> counts{};       // samples per stratum
  std::array<int, kStrata> from_camera{};  // of them at camera-visible points
  int stratum_min = 0;
  double oracle_ms = 0.0;
  int count(Stratum s) const { return counts[size_t(s)]; }
  // Whether a stratum holds samples, fewer than stratum_min (its p95 is not estimated).
  bool few(Stratum s) const { return count(s) > 0 && count(s) < stratum_min; }
  // "lit 1800 (all camera), umbra 200 (12 camera), ...; few: partial (31)".
  std::string counts_text() const;
};

// What the exact oracle answers at points: per point and light the transmittance, [point *
// light_count + light], its light count and time.
struct OracleAnswers {
  std::vector<double> transmittance;
  int light_count = 0;
  double milliseconds = 0.0;
};
using Oracle = std::function<OracleAnswers(const std::vector<dvec3>& points)>;

// The stratified points of the scene (`host`: its data in host memory) as `camera` sees it
// (`sight`: its visible surface at the camera's size), with `media` points when the scene has
// media; `oracle` answers the transmittance.
StratifiedProbes make_stratified_probes(const Scene& scene, const SceneData& host,
                                        const VisibleSurface& sight, const Camera& camera,
                                        bool media, const StrataSettings& settings,
                                        const Oracle& oracle);

// The error of one stratum: count, p95 and max of |T' - T|, and the p95's upper 95 % confidence
// bound (the error at rank ceil(0.95 n + 1.645 sqrt(0.0475 n)), the normal approximation of the
// binomial order statistic; the max for small n); `few` as StratifiedProbes::few.
struct StratumError {
  int count = 0;
  double p95 = 0.0, max = 0.0;
  bool few = false;
  double p95_upper = 0.0;
  // What the budget compares: the p95's upper bound, so that a configuration whose errors sit
  // near the 95th percentile of a few hundred samples is not passed by chance (a search seed
  // that happens to see under 5 % wrong points); the max where the p95 cannot be estimated.
  double judged() const { return few ? max : p95_upper; }
};
// Per stratum the error of `transmittance` ([point * light_count + light] at probes.points).
std::array<StratumError, kStrata> stratum_errors(const StratifiedProbes& probes,
                                                 const std::vector<double>& transmittance);
// What an error bound E is checked against: the worst stratum's judged error (0 with no
// samples); and the largest error of any sample.
double worst_judged(const std::array<StratumError, kStrata>& errors);
double largest_error(const std::array<StratumError, kStrata>& errors);

}  // namespace dv
