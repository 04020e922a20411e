// Effect sizes with 95 % intervals for the findings' verdicts (findings.h), by bootstrap with a
// fixed seed so a report is the same every time it is built. Two kinds of data:
// - measurements repeated in independent process runs (timings, and counts that may vary from
//   run to run): per item, per run, the samples of that run. The effect is the ratio of the two
//   sides' means (a side's mean: the mean over its items of each item's mean sample); its
//   interval is a two-stage cluster bootstrap: draw the runs with replacement (one draw shared by
//   every item of both sides, since drift moves a whole run), then each drawn run's samples with
//   replacement within it. With one run the interval holds only the repetitions' spread.
//   When the second side's mean is 0 the effect is the difference instead.
// - errors at probe points (the probes are deterministic per scene, so two items of one scene
//   were measured at the same points): per item the signed errors. The effect is the difference
//   of the two sides' means of a statistic of |error| (mean, max or p99 over the points); its
//   interval is a paired bootstrap: per resample one draw of point indices per pairing group
//   (the scene), applied to every item of that group on both sides.
// The interval is the 2.5 and 97.5 percentiles of the resampled effects.
// "No effect" is a band for ratios, not the point 1: a ratio within 1 % of 1 (kSmallestRatio)
// counts as no effect, so a count that does not vary between runs (layers, bytes, voxels: a
// zero-width interval) does not confirm a claim by 0.05 %. Differences (probe errors) keep 0:
// their intervals come from the spread over the points.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace dv {

constexpr double kSmallestRatio = 0.01;

struct EffectInterval {
  double effect = 0.0, low = 0.0, high = 0.0;
  bool ratio = true;  // ratio of means (no effect: 1), else difference (no effect: 0)
  double none() const { return ratio ? 1.0 : 0.0; }
  // Entirely below / above the band of "no effect" (ratios: 1 / (1 + kSmallestRatio) to
  // 1 + kSmallestRatio; differences: 0).
  bool below() const { return high < (ratio ? 1.0 / (1.0 + kSmallestRatio) : 0.0); }
  bool above() const { return low > (ratio ? 1.0 + kSmallestRatio : 0.0); }
};

constexpr int kResamples = 2000;

// Per item: per run the samples of that run ([run][sample]). Items without samples are left
// out by the caller; both sides non-empty.
using RunSamples = std::vector<std::vector<double>>;
// A side's mean: the mean over its items of each item's mean over all its samples.
double side_mean(const std::vector<RunSamples>& side);
// `difference`: the effect is the difference of the means (an overhead), not their ratio.
EffectInterval cluster_bootstrap(const std::vector<RunSamples>& first,
                                 const std::vector<RunSamples>& second, uint64_t seed,
                                 bool difference = false);

// One item's signed errors at its probe points, and its pairing group (items of one group have
// the same points, in the same order).
struct PointErrors {
  const std::vector<double>* errors = nullptr;
  std::string group;
};
// `statistic`: "mean", "max" or "p99" (nearest rank, as error_summary.h).
EffectInterval paired_bootstrap(const std::vector<PointErrors>& first,
                                const std::vector<PointErrors>& second,
                                const std::string& statistic, uint64_t seed);

// A seed from text (a claim): FNV-1a, so every claim has its own reproducible stream.
uint64_t seed_of(const std::string& text);

}  // namespace dv
