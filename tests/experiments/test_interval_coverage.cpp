// The findings' interval over runs (effect_interval.h) covers a known effect 95 % of the time on
// simulated runs whose between-run variance dominates, as timings on a GPU do: each side's run
// mean drifts by its own factor from run to run (5 % standard deviation on the log scale) while
// the repetitions within a run scatter by 1 %. With 3 and 5 runs the coverage of the true ratio
// (and, with `difference`, of the true difference) must lie within 93-97 %, and an A/A pair
// (no true effect) must rarely be called different. The random numbers come from mt19937_64 and
// a Box-Muller transform written here, so every platform simulates the same runs.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "experiments/harness/effect_interval.h"

namespace dv {
namespace {

class Normal {
 public:
  explicit Normal(uint64_t seed) : rng_(seed) {}
  double operator()() {
    const double u1 = (double(rng_() >> 11) + 0.5) * 0x1p-53;
    const double u2 = double(rng_() >> 11) * 0x1p-53;
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
  }

 private:
  std::mt19937_64 rng_;
};

constexpr double kBetweenRuns = 0.05;  // log-scale standard deviation of a run's drift
constexpr double kWithinRun = 0.01;    // relative standard deviation of a repetition
constexpr int kRepetitions = 5;
constexpr int kItemsPerSide = 2;
constexpr int kTrials = 4000;

// One side: its items, each measured in `runs` runs with its own drift per run around `mean`.
std::vector<RunSamples> simulate_side(double mean, int runs, Normal& normal) {
  std::vector<RunSamples> side(kItemsPerSide);
  for (RunSamples& item : side)
    for (int r = 0; r < runs; ++r) {
      const double run_mean = mean * std::exp(kBetweenRuns * normal());
      std::vector<double> samples;
      for (int k = 0; k < kRepetitions; ++k)
        samples.push_back(run_mean * (1.0 + kWithinRun * normal()));
      item.push_back(std::move(samples));
    }
  return side;
}

struct Coverage {
  double covered = 0.0, called_different = 0.0;  // fractions of the trials
};

Coverage simulate(double first_mean, double second_mean, int runs, bool difference, uint64_t seed) {
  // The per-run log ratio's expectation is log(first / second): the drifts are centred on the
  // log scale and the repetitions' bias is the same on both sides. For differences the drift's
  // mean exp(s^2 / 2) scales both sides.
  const double drift_mean = std::exp(0.5 * kBetweenRuns * kBetweenRuns);
  const double truth =
      difference ? (first_mean - second_mean) * drift_mean : first_mean / second_mean;
  Normal normal(seed);
  int covered = 0, different = 0;
  for (int t = 0; t < kTrials; ++t) {
    const std::vector<RunSamples> a = simulate_side(first_mean, runs, normal);
    const std::vector<RunSamples> b = simulate_side(second_mean, runs, normal);
    const RunInterval ri = run_interval(a, b, difference);
    EXPECT_EQ(ri.runs, size_t(runs));
    covered += ri.interval.low <= truth && truth <= ri.interval.high;
    different += ri.interval.below() || ri.interval.above();
  }
  return {double(covered) / kTrials, double(different) / kTrials};
}

TEST(IntervalCoverage, RatiosWithThreeAndFiveRuns) {
  for (int runs : {3, 5}) {
    const Coverage c = simulate(0.8, 1.0, runs, false, 55 + uint64_t(runs));
    EXPECT_GE(c.covered, 0.93) << runs << " runs";
    EXPECT_LE(c.covered, 0.97) << runs << " runs";
  }
}

TEST(IntervalCoverage, DifferencesWithThreeAndFiveRuns) {
  for (int runs : {3, 5}) {
    const Coverage c = simulate(1.5, 2.0, runs, true, 550 + uint64_t(runs));
    EXPECT_GE(c.covered, 0.93) << runs << " runs";
    EXPECT_LE(c.covered, 0.97) << runs << " runs";
  }
}

TEST(IntervalCoverage, AnAAPairIsRarelyCalledDifferent) {
  for (int runs : {3, 5}) {
    const Coverage c = simulate(2.0, 2.0, runs, false, 5500 + uint64_t(runs));
    EXPECT_GE(c.covered, 0.93) << runs << " runs";
    EXPECT_LE(c.called_different, 0.05) << runs << " runs";
  }
}

}  // namespace
}  // namespace dv
