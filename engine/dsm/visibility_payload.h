// The deep-shadow-map pass's payload for the fragment walk (engine/raster/fragment_walk.h): along a
// ray from the light it tracks the visibility V (transmittance from the light) and feeds a
// visibility function to a target (the streaming compressor, engine/dsm/visibility_compressor.h) as
// samples (z, V) at float32 depths z = the ray parameter (distance from the light, or from an
// orthographic map's near plane):
// - a surface crossing: a step V -> V (1 - a) at its depth (twin nodes), a the crossing's
//   opacity (engine/scene/surface_transmittance.h: alpha, a texture's coverage at the crossing,
//   or for glass one minus the luminance of what the crossing lets through at the ray's angle);
// - volumes: the renderer's step rules (engine/raster/media_march.h), V after each step sampled at
// the
//   step's end, so the interpolant matches the camera pass's midpoint quadrature at step ends;
//   or, with pre-compressed tables (engine/dsm/precompressed_table.h) and one volume at a time, the
//   table's nodes inside each step from the densities at its two ends;
// - constant media: exact values exp(-sigma d), sampled densely enough that the linear
//   interpolant stays within eps / 2 of the exponential (the chord error of exp(-x) over a step h
//   is at most (sigma h)^2 / 8), and at least at both ends.
// The function starts at the first crossing (or where the walk starts inside a medium) with V = 1.
// With track_colour the payload also sums, up to the first opaque crossing, the optical depth
// of V (-ln of each factor) and the per-channel optical depth of the crossing rule and the
// media's sigma_rgb, and keeps the sums where the last tinted stretch ended: their ratio there
// and that depth are the texel's colour side channel (dsm_colour.h).
// Host and device code.
#pragma once

#include <cmath>
#include <cstdint>

#include "core/hd.h"
#include "core/math.h"
#include "engine/dsm/precompressed_table.h"
#include "engine/raster/fragment_walk.h"
#include "engine/raster/media_march.h"
#include "engine/scene/surface_transmittance.h"

namespace dv {

// Visibility below which a DSM ray stops: everything behind is dark within any useful eps.
inline constexpr double kDsmSaturatedVisibility = 1e-6;
// Most samples one constant-medium segment is split into.
inline constexpr int kMaxConstantMediumSamples = 1024;

// What a colour-tracking walk summed (VisibilityPayload::track_colour), up to the end of the
// last tinted stretch (a crossing or a constant medium whose channels differ): beyond it every
// layer is grey. tinted_end < 0: nothing along the ray tints.
struct ColourDepth {
  double optical_depth = 0.0;
  dvec3 optical_depth_rgb{0.0};
  double tinted_end = -1.0;
};

// Target interface: void push(float z, float v); void push_step(float z, float before, float
// after).
template <class Target>
struct VisibilityPayload {
  const SceneView& s;
  Target& target;
  dvec3 origin;
  dvec3 dir;
  double eps;
  double visibility = 1.0;
  PrecompressedTables tables{};  // bins == 0: midpoint sampling
  double step_scale = 1.0;       // multiplies the volumes' steps
  bool started = false;
  unsigned long long samples = 0;
  bool track_colour = false;     // sum the optical depths below
  double optical_depth = 0.0;    // of V, up to the first opaque crossing
  dvec3 optical_depth_rgb{0.0};  // per channel, the same stretch
  dvec3 segment_sigma_rgb{0.0};  // the constant media's per-channel extinction (track_colour)
  ColourDepth tinted{};          // the sums where the last tinted stretch ended (track_colour)

  DV_HD bool done() const { return visibility <= kDsmSaturatedVisibility; }

  DV_HD void surface(const RayHit& h, int32_t object) {
    const ObjectView& o = s.objects[object];
    if (material_coverage(o) <= 0.0) return;
    const dvec3 p = origin + dir * h.t;
    const double alpha = crossing_opacity(s, o, h.triangle, dir, p);
    if (alpha <= 0.0) return;
    const double after = alpha >= 1.0 ? 0.0 : visibility * (1.0 - alpha);
    if (track_colour && alpha < 1.0) {
      const dvec3 t = crossing_transmittance(s, o, h.triangle, dir, p);
      optical_depth -= log(1.0 - alpha);
      optical_depth_rgb -= dvec3(log(t.x), log(t.y), log(t.z));
      if (!(t.x == t.y && t.y == t.z)) note_tinted_end(h.t);
    }
    target.push_step(float(h.t), float(visibility), float(after));
    started = true;
    visibility = after;
  }

  DV_HD void segment(const InsideSet& inside, double t0, double t1) {
    if (!started) {
      target.push(float(t0), 1.0f);
      started = true;
    }
    if (track_colour) segment_sigma_rgb = constant_extinction_rgb(s, inside);
    march_media(s, inside, origin, dir, t0, t1, *this, step_scale);
  }

  // The colour sums so far end the last tinted stretch at depth `end`.
  DV_HD void note_tinted_end(double end) { tinted = {optical_depth, optical_depth_rgb, end}; }

  // Adds a stretch of `length` ending at depth `end` with scalar extinction `sigma` = constant +
  // volume part, whose constant media have per-channel extinction segment_sigma_rgb
  // (track_colour only).
  DV_HD void add_colour_depth(double sigma, double sigma_constant, double length, double end) {
    if (!track_colour) return;
    optical_depth += sigma * length;
    optical_depth_rgb += (segment_sigma_rgb + dvec3(sigma - sigma_constant)) * length;
    const dvec3& c = segment_sigma_rgb;
    if (length > 0.0 && !(c.x == c.y && c.y == c.z)) note_tinted_end(end);
  }

  DV_HD void absorb(double sigma_constant, double a, double b) {
    if (b <= a) return;
    add_colour_depth(sigma_constant, sigma_constant, b - a, b);
    if (sigma_constant <= 0.0) {  // an empty stretch: V is flat up to b
      target.push(float(b), float(visibility));
      return;
    }
    const double tolerance = max_value(eps, 1e-4);
    const double optical = sigma_constant * (b - a);
    const int n =
        int(min_value(ceil(optical / sqrt(4.0 * tolerance)), double(kMaxConstantMediumSamples)));
    const double v0 = visibility;
    for (int k = 1; k <= max_value(n, 1); ++k) {
      const double t = k == n ? b : a + (b - a) * double(k) / double(n);
      visibility = v0 * exp(-sigma_constant * (t - a));
      target.push(float(t), float(visibility));
      ++samples;
      if (done()) return;
    }
  }

  DV_HD void sample(const InsideSet& inside, double sigma_constant, const dvec3& x, double a,
                    double b) {
    ++samples;
    const int32_t volume = single_volume(inside);
    if (volume >= 0 && tables.bins > 0 && tables.has(volume)) {
      tabled_step(volume, sigma_constant, a, b);
      return;
    }
    const double sigma = sigma_constant + volume_extinction(s, inside, x);
    add_colour_depth(sigma, sigma_constant, b - a, b);
    visibility *= exp(-sigma * (b - a));
    target.push(float(b), float(visibility));
  }

  // The one volume object the ray is inside, or -1 (none or several).
  DV_HD int32_t single_volume(const InsideSet& inside) const {
    int32_t found = -1;
    for (int i = 0; i < inside.count; ++i) {
      if (s.objects[inside.object[i]].interior != InteriorKind::volume) continue;
      if (found >= 0) return -1;
      found = inside.object[i];
    }
    return found;
  }

  // One step with a pre-compressed table (precompressed_table.h): the table's nodes for the
  // nearest density nodes, each moved to where the step's own linear density equals the table's
  // density at it (kept as a fraction where the two ramps differ in direction or the table's is
  // flat), and V there and at the step's end from the exact mean extinction of the ramp.
  DV_HD void tabled_step(int32_t object, double sigma_constant, double a, double b) {
    const ObjectView& o = s.objects[object];
    const VolumeView& v = s.volumes[o.volume];
    const TransferPoint* tf = s.transfer.data + o.transfer_first;
    const double d0 = density_at_grid(s, v, world_to_grid(o, origin + dir * a));
    const double d1 = density_at_grid(s, v, world_to_grid(o, origin + dir * b));
    const int i = tables.node(object, d0), j = tables.node(object, d1);
    const double t0 = tables.node_density(object, i), t1 = tables.node_density(object, j);
    const bool by_density = (t1 - t0) * (d1 - d0) > 0.0;
    const PrecompressedStep& step = tables.step(object, i, j);
    const double dt = b - a, v0 = visibility;
    double last = 0.0;
    for (int k = 0; k < step.count; ++k) {
      const double s_k = double(step.s[k]);
      const double u = by_density ? (t0 + (t1 - t0) * s_k - d0) / (d1 - d0) : s_k;
      if (!(u > last && u < 1.0)) continue;
      last = u;
      const double optical =
          dt * u * transfer_sigma_mean(tf, o.transfer_count, d0, d0 + (d1 - d0) * u);
      target.push(float(a + u * dt), float(v0 * exp(-optical - sigma_constant * u * dt)));
    }
    const double mean = transfer_sigma_mean(tf, o.transfer_count, d0, d1);
    add_colour_depth(mean + sigma_constant, sigma_constant, dt, b);
    visibility = v0 * exp(-dt * (mean + sigma_constant));
    target.push(float(b), float(visibility));
  }
};

}  // namespace dv
