// Streaming compression of one deep-shadow-map texel's visibility function with an error bound:
// the slope wedge of Lokovic & Veach 2000, as Knecht 2011 Algorithm 3.2 describes it, made safe
// (monotone, bounded under float rounding, eps = 0 allowed). The generation walk's visibility
// payload feeds it per sample and per surface crossing; the nodes go to a pluggable sink (the
// storage strategies). Host and device code: no allocation, no recursion, no exceptions.
//
// Input: samples (z, v) of the visibility V (1 at the light, non-increasing) at non-decreasing
// float32 distances z from the light; a surface crossing is push_step(z, before, after), two
// samples at the same z. V is the piecewise-linear interpolant of the samples, with a step
// wherever two samples share a z, 1 before the first sample and the last value after the last.
// Output: nodes (z, v) that define V' the same way. For eps >= 0 the compressor guarantees
// |V'(z) - V(z)| <= eps for all z (on both sides of steps), V' non-increasing and in [0, 1].
//
// Node placement: a segment starts at an origin node; each later sample k narrows the wedge of
// slopes m <= 0 for which the line through the origin passes within the band
// [max(v_k - e, 0), v_k + e] at z_k. When a sample empties the wedge, a node is emitted at the
// previous sample's depth z_p with the value nearest to V(z_p) that some slope of the wedge
// reaches, clamped so it never exceeds the origin (no increase) and stays within e of V(z_p);
// it becomes the next origin. Since both V and V' are linear between consecutive sample depths,
// checking the band at the samples bounds the error everywhere. The band half-width e is eps
// shrunk by a few float32 roundings, so the bound also holds for the rounded arithmetic; when
// nothing is left (eps below ~2e-6, e.g. 0) the compressor keeps a node at every sample where
// V bends and merges only runs of equal v, which is exact.
#pragma once

#include "core/hd.h"
#include "core/math.h"

namespace dv {

// What one texel's compression produced.
struct VisibilityCompressionStats {
  int nodes = 0;          // nodes V' needs, also those a full sink refused
  bool overflow = false;  // the sink refused a node: it holds only a prefix of V'
  // An upper bound (up to float rounding) on the max |V' - V| actually reached, at most eps:
  // exact where V' is flat, per segment the smaller of two cheap bounds elsewhere.
  float max_error = 0.0f;
};

// A sink that only counts (the counting pass of exact-size storages); never refuses.
struct CountingNodeSink {
  int count = 0;
  DV_HD bool emit(float, float) {
    ++count;
    return true;
  }
};

// A sink writing into caller-owned (z, v) arrays of fixed capacity; refuses when full.
struct ArrayNodeSink {
  float* z = nullptr;
  float* v = nullptr;
  int capacity = 0;
  int count = 0;
  DV_HD bool emit(float node_z, float node_v) {
    if (count >= capacity) return false;
    z[count] = node_z, v[count] = node_v, ++count;
    return true;
  }
};

// Sink interface: `bool emit(float z, float v)`, false when it has no room. After the first
// refusal the compressor calls emit no more but keeps counting the nodes V' needs.
template <class Sink>
class VisibilityCompressor {
 public:
  // eps below 0 (or NaN) acts as 0; eps above 4 acts as 4 (any eps >= 1 already admits V' = 1).
  DV_HD explicit VisibilityCompressor(float eps, Sink sink = Sink{}) : sink_(sink) {
    eps_ = eps > 0.0f ? min_value(eps, 4.0f) : 0.0f;
    band_ = eps_ - kRoundingAllowance * (1.0f + eps_);
    exact_ = !(band_ > 0.0f);
    if (exact_) band_ = 0.0f;
  }

  // A sample of V at depth z. z below the previous sample's is raised to it, v is clamped into
  // [0, previous v]; samples with a non-finite z or NaN v are ignored.
  DV_HD void push(float z, float v) {
    if (finished_ || !(z - z == 0.0f) || v != v) return;
    if (started_) {
      z = max_value(z, last_z_);
      v = min_value(v, last_v_);
    } else {
      v = min_value(v, 1.0f);
    }
    v = max_value(v, 0.0f);
    last_z_ = z, last_v_ = v;
    add_sample(z, v);
  }

  // A surface crossing at z: V drops from v_before to v_after there (twin nodes in V').
  DV_HD void push_step(float z, float v_before, float v_after) {
    push(z, v_before);
    push(z, v_after);
  }

  // Ends the function: emits what is still pending. Later pushes are ignored.
  DV_HD void finish() {
    if (finished_ || !started_) {
      finished_ = true;
      return;
    }
    finished_ = true;
    if (has_run_) {
      const bool flat = exact_ ? run_flat_ : hi_ >= 0.0f;
      if (flat) {
        // V' stays at the origin's value: every run sample and the tail are within the band.
        note_error(max_value(origin_v_ - run_last_v_, run_first_v_ - origin_v_));
      } else {
        end_segment();
      }
    }
    emit_pending_origin();
  }

  DV_HD const VisibilityCompressionStats& stats() const { return stats_; }
  DV_HD Sink& sink() { return sink_; }
  DV_HD const Sink& sink() const { return sink_; }
  DV_HD float eps() const { return eps_; }

 private:
  // Relative allowance for float32 rounding in the wedge and node arithmetic: 32 units of
  // roundoff (2^-19), several times the first-order error of the few operations involved.
  static constexpr float kRoundingAllowance = 1.0f / 524288.0f;

  DV_HD void add_sample(float z, float v) {
    if (!started_) {
      started_ = true;
      origin_z_ = z, origin_v_ = v, origin_emitted_ = false;
      return;
    }
    if (has_run_) {
      if (extend_run(z, v)) return;
      end_segment();  // the origin moves to the last accepted sample; z >= that depth
    }
    if (z == origin_z_) {
      sample_at_origin(v);
      return;
    }
    emit_pending_origin();
    begin_run(z, v);
  }

  // A sample at the origin's depth. Only V's one-sided limits matter there, so a pending
  // after-twin simply follows the latest sample (coincident surfaces give one twin, exact);
  // otherwise the sample is within the band of the origin, or a step that needs a twin node.
  DV_HD void sample_at_origin(float v) {
    const bool pending_twin = !origin_emitted_ && any_emitted_ && last_emitted_z_ == origin_z_;
    if (pending_twin) {
      origin_v_ = v;
      return;
    }
    const float error = origin_v_ > v ? origin_v_ - v : v - origin_v_;
    if (error <= band_) {
      note_error(error);
      return;
    }
    emit_pending_origin();
    origin_v_ = v, origin_emitted_ = false;
  }

  // The first sample beyond the origin: its wedge alone is never empty.
  DV_HD void begin_run(float z, float v) {
    has_run_ = true;
    run_flat_ = v == origin_v_;
    run_first_v_ = v;
    const float dz = z - origin_z_;
    const float slope = (v - origin_v_) / dz;
    slope_min_ = slope_max_ = slope;
    hi_ = min_value((v + band_ - origin_v_) / dz, 0.0f);
    lo_ = min_value((max_value(v - band_, 0.0f) - origin_v_) / dz, hi_);
    run_last_z_ = z, run_last_v_ = v;
  }

  // Narrows the wedge by one more sample; false (and unchanged) when the wedge would be empty.
  DV_HD bool extend_run(float z, float v) {
    if (exact_) {
      if (!(run_flat_ && v == origin_v_)) return false;
      run_last_z_ = z, run_last_v_ = v;
      return true;
    }
    const float dz = z - origin_z_;
    const float lo = max_value(lo_, (max_value(v - band_, 0.0f) - origin_v_) / dz);
    const float hi = min_value(hi_, (v + band_ - origin_v_) / dz);
    if (lo > hi) return false;
    lo_ = lo, hi_ = hi;
    const float slope = (v - origin_v_) / dz;
    slope_min_ = min_value(slope_min_, slope);
    slope_max_ = max_value(slope_max_, slope);
    run_last_z_ = z, run_last_v_ = v;
    return true;
  }

  // Emits the node closing the current run at its last sample and makes it the origin.
  DV_HD void end_segment() {
    const float z = run_last_z_, target = run_last_v_;
    float value = target;
    if (!exact_) {
      const float dz = z - origin_z_;
      value = clamp_value(target, origin_v_ + lo_ * dz, origin_v_ + hi_ * dz);
      value = max_value(value, max_value(target - band_, 0.0f));
      value = min_value(value, origin_v_);
      const float slope = (value - origin_v_) / dz;
      const float by_slopes = dz * max_value(slope - slope_min_, slope_max_ - slope);
      const float by_values = max_value(origin_v_ - target, run_first_v_ - value);
      note_error(min_value(by_slopes, by_values));
    }
    emit(z, value);
    origin_z_ = z, origin_v_ = value, origin_emitted_ = true;
    has_run_ = false;
  }

  DV_HD void emit_pending_origin() {
    if (origin_emitted_) return;
    emit(origin_z_, origin_v_);
    origin_emitted_ = true;
  }

  DV_HD void emit(float z, float v) {
    ++stats_.nodes;
    any_emitted_ = true, last_emitted_z_ = z;
    if (!stats_.overflow && !sink_.emit(z, v)) stats_.overflow = true;
  }

  DV_HD void note_error(float error) {
    stats_.max_error = min_value(max_value(stats_.max_error, error), eps_);
  }

  Sink sink_;
  VisibilityCompressionStats stats_;
  float eps_ = 0.0f;
  float band_ = 0.0f;  // half-width of the band each sample puts on V'
  bool exact_ = true;  // no band left after the rounding allowance: keep every bend
  bool started_ = false, finished_ = false;
  float last_z_ = 0.0f, last_v_ = 1.0f;  // the previous sample, for sanitising the input
  float origin_z_ = 0.0f, origin_v_ = 1.0f;
  bool origin_emitted_ = false;
  bool any_emitted_ = false;
  float last_emitted_z_ = 0.0f;
  bool has_run_ = false;   // samples beyond the origin's depth are being merged
  bool run_flat_ = false;  // every run sample equals the origin's value
  float run_first_v_ = 1.0f, run_last_z_ = 0.0f, run_last_v_ = 1.0f;
  float lo_ = 0.0f, hi_ = 0.0f;                // the slope wedge
  float slope_min_ = 0.0f, slope_max_ = 0.0f;  // slopes from the origin to the run samples
};

}  // namespace dv
