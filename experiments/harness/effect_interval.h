// Effect sizes with 95 % intervals for the findings' verdicts (findings.h). Two kinds of data:
// - measurements repeated in independent process runs (timings, and counts that may vary from
//   run to run): per item, per run, the samples of that run. Runs, not repetitions, are the
//   unit: drift between runs moves a whole run (its between-run variance of a run's mean was
//   about 16 times the within-run variance on the H200), so per run the effect is the ratio of
//   the two sides' means in that run (a side's mean: the mean over its items of each item's mean
//   sample), and the interval is Student's t with n - 1 degrees of freedom over those n per-run
//   effects, on the log scale (back-transformed: the effect is the geometric mean of the per-run
//   ratios). A bootstrap over 3 runs spans about their min..max and covers far less than 95 %.
//   Only runs in which every item of both sides was measured count; fewer than 2 give no
//   interval. When a side's mean is not positive in some run the effect is the difference of
//   the means instead (t on the per-run differences).
// - errors at probe points (the probes are deterministic per scene, so two items of one scene
//   were measured at the same points): per item the signed errors. The effect is the difference
//   of the two sides' means of a statistic of |error| (mean, max or p99 over the points); its
//   interval is a paired bootstrap with a fixed seed (a report is the same every time it is
//   built): per resample one draw of point indices per pairing group (the scene), applied to
//   every item of that group on both sides; the interval is the 2.5 and 97.5 percentiles of the
//   resampled effects.
// "No effect" is a band for ratios, not the point 1: a ratio within 1 % of 1 (kSmallestRatio)
// counts as no effect, so a count that does not vary between runs (layers, bytes, voxels: a
// zero-width interval) does not confirm a claim by 0.05 %. Differences (probe errors, counts that
// are 0 in some run) have no band unless the suite states a practical band for the metric
// ("practical_bands": a difference smaller than it does not matter, e.g. a fraction of the
// error itself); their intervals come from the spread over the points or the runs.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace dv {

constexpr double kSmallestRatio = 0.01;

struct EffectInterval {
  double effect = 0.0, low = 0.0, high = 0.0;
  bool ratio = true;  // ratio of means (no effect: 1), else difference (no effect: 0)
  // Ratios: the relative half-width of "no effect", kSmallestRatio or wider where A/A controls
  // measured a wider spread between identical configurations (aa_controls.h).
  double band = kSmallestRatio;
  // Differences: the half-width of "no effect" in the metric's unit (a practical band), 0 when
  // the suite states none.
  double difference_band = 0.0;
  double none() const { return ratio ? 1.0 : 0.0; }
  // Entirely below / above the band of "no effect" (ratios: 1 / (1 + band) to 1 + band;
  // differences: -difference_band to +difference_band).
  bool below() const { return high < (ratio ? 1.0 / (1.0 + band) : -difference_band); }
  bool above() const { return low > (ratio ? 1.0 + band : difference_band); }
};

// Per metric: the tie band (EffectInterval::band) that A/A controls measured.
using TieBands = std::map<std::string, double>;
// Per column ("metric:stat") or metric: the practical band of differences
// (EffectInterval::difference_band), as the suite states it ("practical_bands").
using PracticalBands = std::map<std::string, double>;

constexpr int kResamples = 2000;

// Per item: per run the samples of that run ([run][sample]); a run in which the item was not
// measured is empty (or past the end). Items without samples are left out by the caller.
using RunSamples = std::vector<std::vector<double>>;
// A side's mean: the mean over its items of each item's mean over all its samples.
double side_mean(const std::vector<RunSamples>& side);

// The 95 % Student-t interval of per-run effects (at least 2): `ratio`: positive ratios, whose
// logarithms are averaged and the interval back-transformed; else differences as they are.
EffectInterval t_interval(const std::vector<double>& per_run_effects, bool ratio);

struct RunInterval {
  EffectInterval interval;
  size_t runs = 0;  // the runs it rests on; below 2 `interval` is not set
};
// The first side against the second, run by run (see above); `difference`: the effect is the
// difference of the means (an overhead), not their ratio.
RunInterval run_interval(const std::vector<RunSamples>& first,
                         const std::vector<RunSamples>& second, bool difference = false);

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
