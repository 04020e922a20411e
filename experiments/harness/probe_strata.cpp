// Stratified probe points and their errors (probe_strata.h).
#include "experiments/harness/probe_strata.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>

#include "engine/oracle/transmittance.h"
#include "engine/raster/raster_projection.h"
#include "engine/raster/shadow_receiver.h"
#include "engine/scene/ray_query.h"
#include "engine/scene/texture_sampling.h"
#include "experiments/harness/error_summary.h"
#include "experiments/harness/probe_points.h"

namespace dv {

namespace {

// The light view's draws: rounds of candidate surface points, as many per round as this times
// the stratum minimum, at most this many rounds (and none after a round that added nothing).
constexpr int kLightViewCandidatesPerMin = 4;
constexpr int kLightViewRounds = 8;
// The camera's further pixels come in batches of this times the first draw.
constexpr int kCameraBatchFactor = 4;
// Seeds of the light view's rounds: the settings' seed plus this times the round (apart from
// the seeds the search and its verification use).
constexpr uint64_t kLightViewSeedStride = 7919;

class Builder {
 public:
  Builder(const SceneData& host, const dvec3& eye, const StrataSettings& s, const Oracle& oracle)
      : host_(host), eye_(eye), settings_(s), oracle_(oracle) {
    out_.light_count = int(host.host_lights().size());
    out_.stratum_min = s.stratum_min;
  }

  bool shadow_short() const {
    return short_stratum(Stratum::umbra) || short_stratum(Stratum::partial);
  }
  bool surface_short() const { return shadow_short() || short_stratum(Stratum::lit); }

  // Adds `points` from `source`: every sample (`all_samples`) or only those of the short
  // strata among `fill` (a point without one is dropped).
  void add(const std::vector<dvec3>& points, ProbeSource source, bool all_samples,
           std::initializer_list<Stratum> fill = {}) {
    if (points.empty()) return;
    const OracleAnswers a = oracle_(points);
    out_.oracle_ms += a.milliseconds;
    const size_t lights = size_t(out_.light_count);
    std::array<bool, kStrata> wanted;
    wanted.fill(all_samples);
    for (Stratum s : fill) wanted[size_t(s)] = wanted[size_t(s)] || short_stratum(s);
    for (size_t p = 0; p < points.size(); ++p) {
      std::vector<StratumSample> kept;
      for (size_t l = 0; l < lights; ++l) {
        LightSegment segment;
        if (!make_light_segment(host_.view(), host_.host_lights()[l], points[p], segment))
          continue;  // outside a spot light's cone: T = 0 by the cone, no shadow
        if (source != ProbeSource::medium && faces_away(host_.host_lights()[l], segment, points[p]))
          continue;  // the light cannot reach the surface's seen side: its T is never used
        const double exact = a.transmittance[p * lights + l];
        const Stratum s = source == ProbeSource::medium ? Stratum::media : surface_stratum(exact);
        if (wanted[size_t(s)]) kept.push_back({uint32_t(out_.points.size()), uint16_t(l), s});
      }
      if (kept.empty()) continue;
      for (const StratumSample& k : kept) {
        out_.samples.push_back(k);
        ++out_.counts[size_t(k.stratum)];
        if (source == ProbeSource::camera) ++out_.from_camera[size_t(k.stratum)];
      }
      out_.points.push_back(points[p]);
      out_.sources.push_back(source);
      out_.exact.insert(out_.exact.end(), a.transmittance.begin() + std::ptrdiff_t(p * lights),
                        a.transmittance.begin() + std::ptrdiff_t((p + 1) * lights));
    }
  }

  size_t sample_count() const { return out_.samples.size(); }
  StratifiedProbes take() { return std::move(out_); }

 private:
  bool short_stratum(Stratum s) const { return out_.count(s) < settings_.stratum_min; }

  // Whether the surface at `p`, on the side the camera sees, faces away from the light (the
  // renderer's n . l <= 0: no direct light whatever the transmittance), judged by the geometric
  // normal of the surface the shadow lookup finds there.
  bool faces_away(const LightView& light, const LightSegment& segment, const dvec3& p) const {
    dvec3 n = probe_receiver(host_.view(), light, p).normal;
    if (glm::dot(n, n) == 0.0) return false;
    if (glm::dot(n, eye_ - p) < 0.0) n = -n;
    return glm::dot(n, -segment.dir) <= 0.0;
  }

  const SceneData& host_;
  dvec3 eye_;
  StrataSettings settings_;
  const Oracle& oracle_;
  StratifiedProbes out_;
};

// Whether the camera sees `p`: inside its frustum and the nearest surface with alpha > 0 along
// the ray from its eye (as visible_surface.h looks) is at `p`, within a relative tolerance.
bool seen_by_camera(const SceneView& view, const RasterProjection& projection, const dvec3& eye,
                    const dvec3& p) {
  const dvec4 clip = world_to_clip_point(projection, p);
  if (near_plane_distance(projection, clip) < 0.0 || std::abs(clip.x) > clip.w ||
      std::abs(clip.y) > clip.w)
    return false;
  const double distance = glm::length(p - eye);
  if (distance <= 0.0) return false;
  const dvec3 dir = (p - eye) / distance;
  const double before = distance - 1e-6 * (view.diagonal + distance);
  bool hidden = false;
  for_each_hit(view, make_sheared_ray(eye, dir), 0.0, before, [&](const RayHit& h) {
    const dvec3 x = eye + dir * h.t;
    hidden = surface_alpha(view, h.triangle, x) > 0.0 &&
             near_plane_distance(projection, world_to_clip_point(projection, x)) >= 0.0;
    return !hidden;
  });
  return !hidden;
}

// The nearest surface with alpha > 0 behind `through` as light `light` sees it (its ray
// continued past the point), when there is one.
bool receiver_behind(const SceneView& view, const LightView& light, const dvec3& through,
                     dvec3& receiver) {
  LightSegment segment;
  if (!make_light_segment(view, light, through, segment)) return false;
  const double beyond =
      segment.t_point + 1e-7 * (view.diagonal + (segment.t_point - segment.t_light));
  const ShearedRay ray = make_sheared_ray(segment.origin, segment.dir);
  double nearest = INFINITY;
  for_each_hit(view, ray, beyond, INFINITY, [&](const RayHit& h) {
    if (h.t < nearest && surface_alpha(view, h.triangle, segment.origin + segment.dir * h.t) > 0.0)
      nearest = h.t;
    return true;
  });
  if (!std::isfinite(nearest)) return false;
  receiver = segment.origin + segment.dir * nearest;
  return true;
}

}  // namespace

const char* to_string(Stratum s) {
  switch (s) {
    case Stratum::lit:
      return "lit";
    case Stratum::umbra:
      return "umbra";
    case Stratum::partial:
      return "partial";
    case Stratum::media:
      return "media";
  }
  return "unknown";
}

Stratum surface_stratum(double exact) {
  if (exact >= 1.0 - kLitTolerance) return Stratum::lit;
  if (exact < kUmbraTransmittance) return Stratum::umbra;
  return Stratum::partial;
}

std::string StratifiedProbes::counts_text() const {
  std::string text, few_text;
  for (Stratum s : kAllStrata) {
    const size_t k = size_t(s);
    text += std::string(text.empty() ? "" : ", ") + to_string(s) + " " + std::to_string(counts[k]);
    if (counts[k] > 0) text += " (" + std::to_string(from_camera[k]) + " camera-visible)";
    if (few(s))
      few_text += std::string(few_text.empty() ? "" : ", ") + to_string(s) + " (" +
                  std::to_string(counts[k]) + " < " + std::to_string(stratum_min) + ")";
  }
  if (!few_text.empty()) text += "; too few for a p95, judged by their max: " + few_text;
  return text;
}

StratifiedProbes make_stratified_probes(const Scene& scene, const SceneData& host,
                                        const VisibleSurface& sight, const Camera& camera,
                                        bool media, const StrataSettings& s, const Oracle& oracle) {
  Builder builder(host, camera.position, s, oracle);
  // 1 and 2: the camera's pixels in one uniform draw, the first ones whole.
  const std::vector<dvec3> seen =
      make_visible_probe_points(sight, sight.width * sight.height, s.seed).points;
  const size_t first = std::min(seen.size(), size_t(std::max(s.camera_points, 0)));
  builder.add({seen.begin(), seen.begin() + std::ptrdiff_t(first)}, ProbeSource::camera, true);
  const size_t batch = std::max<size_t>(first, 1) * kCameraBatchFactor;
  for (size_t from = first; from < seen.size() && builder.surface_short(); from += batch) {
    const size_t to = std::min(seen.size(), from + batch);
    builder.add({seen.begin() + std::ptrdiff_t(from), seen.begin() + std::ptrdiff_t(to)},
                ProbeSource::camera, false, {Stratum::lit, Stratum::umbra, Stratum::partial});
  }
  // 3: each light's view of the receivers behind its casters.
  const SceneView& view = host.view();
  const RasterProjection projection = make_camera_projection(camera, view.bounds);
  for (int round = 0; round < kLightViewRounds && builder.surface_short(); ++round) {
    const ProbePoints through =
        make_probe_points(scene, host, kLightViewCandidatesPerMin * std::max(s.stratum_min, 1), 0.0,
                          s.seed + kLightViewSeedStride * uint64_t(round + 1));
    std::vector<dvec3> receivers;
    for (const dvec3& p : through.points) {
      // The uniform point itself where the camera sees it (lit where no caster is between it
      // and a light: what a spot light's narrow cone leaves the camera's pixels too few of).
      if (seen_by_camera(view, projection, camera.position, p)) receivers.push_back(p);
      for (const LightView& light : host.host_lights()) {
        dvec3 r;
        if (receiver_behind(view, light, p, r) &&
            seen_by_camera(view, projection, camera.position, r))
          receivers.push_back(r);
      }
    }
    const size_t before = builder.sample_count();
    builder.add(receivers, ProbeSource::light_view, false,
                {Stratum::lit, Stratum::umbra, Stratum::partial});
    if (builder.sample_count() == before) break;  // the camera sees none of these shadows
  }
  // 4: inside media.
  if (media) {
    const ProbePoints inside =
        make_probe_points(scene, host, std::max(s.camera_points, s.stratum_min), 1.0, s.seed);
    std::vector<dvec3> points;
    for (size_t i = 0; i < inside.points.size(); ++i)
      if (inside.classes[i] == ProbeClass::medium) points.push_back(inside.points[i]);
    builder.add(points, ProbeSource::medium, true);
  }
  return builder.take();
}

std::array<StratumError, kStrata> stratum_errors(const StratifiedProbes& probes,
                                                 const std::vector<double>& transmittance) {
  std::array<std::vector<double>, kStrata> errors;
  const size_t lights = size_t(probes.light_count);
  for (const StratumSample& s : probes.samples) {
    const size_t i = size_t(s.point) * lights + s.light;
    errors[size_t(s.stratum)].push_back(std::abs(transmittance[i] - probes.exact[i]));
  }
  std::array<StratumError, kStrata> out;
  for (Stratum s : kAllStrata) {
    std::vector<double>& e = errors[size_t(s)];
    std::sort(e.begin(), e.end());
    const double upper = e.empty() ? 0.0 : quantile_bound(e, 0.95, 1.645);
    const ErrorSummary summary = summarize_errors(std::move(e));
    out[size_t(s)] = {int(summary.count), summary.p95, summary.max, probes.few(s), upper};
  }
  return out;
}

double worst_judged(const std::array<StratumError, kStrata>& errors) {
  double worst = 0.0;
  for (const StratumError& e : errors) worst = std::max(worst, e.judged());
  return worst;
}

double largest_error(const std::array<StratumError, kStrata>& errors) {
  double largest = 0.0;
  for (const StratumError& e : errors) largest = std::max(largest, e.max);
  return largest;
}

}  // namespace dv
