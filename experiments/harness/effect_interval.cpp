// Bootstrap intervals of effect sizes (effect_interval.h). Indices are drawn as rng() % n from
// mt19937_64 (no std distributions), so the same seed gives the same interval everywhere.
#include "experiments/harness/effect_interval.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

namespace dv {

namespace {

size_t draw(std::mt19937_64& rng, size_t n) {
  return size_t(rng() % n);
}

double mean_of(const std::vector<double>& v) {
  double sum = 0.0;
  for (double x : v) sum += x;
  return v.empty() ? 0.0 : sum / double(v.size());
}

double effect_of(double first, double second, bool ratio) {
  return ratio ? first / second : first - second;
}

EffectInterval percentile_interval(double effect, bool ratio, std::vector<double> resampled) {
  std::sort(resampled.begin(), resampled.end());
  const auto at = [&](double q) {
    const size_t i = size_t(std::floor(q * double(resampled.size() - 1) + 0.5));
    return resampled[std::min(i, resampled.size() - 1)];
  };
  return {effect, at(0.025), at(0.975), ratio};
}

// One item's resampled mean: for each drawn run (mapped into the item's runs), its samples drawn
// with replacement.
double resampled_item_mean(const RunSamples& item, const std::vector<size_t>& runs,
                           std::mt19937_64& rng) {
  double sum = 0.0;
  size_t n = 0;
  for (size_t r : runs) {
    const std::vector<double>& samples = item[r % item.size()];
    for (size_t k = 0; k < samples.size(); ++k) sum += samples[draw(rng, samples.size())], ++n;
  }
  return n ? sum / double(n) : 0.0;
}

double statistic_of(std::vector<double>& values, const std::string& statistic) {
  if (values.empty()) return 0.0;
  if (statistic == "max") return *std::max_element(values.begin(), values.end());
  if (statistic == "p99") {
    const size_t rank = size_t(std::ceil(0.99 * double(values.size())));
    const size_t k = std::max<size_t>(rank, 1) - 1;
    std::nth_element(values.begin(), values.begin() + long(k), values.end());
    return values[k];
  }
  return mean_of(values);
}

}  // namespace

double side_mean(const std::vector<RunSamples>& side) {
  double sum = 0.0;
  for (const RunSamples& item : side) {
    double s = 0.0;
    size_t n = 0;
    for (const auto& run : item)
      for (double x : run) s += x, ++n;
    sum += n ? s / double(n) : 0.0;
  }
  return side.empty() ? 0.0 : sum / double(side.size());
}

EffectInterval cluster_bootstrap(const std::vector<RunSamples>& first,
                                 const std::vector<RunSamples>& second, uint64_t seed,
                                 bool difference) {
  const double a = side_mean(first), b = side_mean(second);
  const bool ratio = !difference && b != 0.0;
  size_t runs = 1;
  for (const auto* side : {&first, &second})
    for (const RunSamples& item : *side) runs = std::max(runs, item.size());
  std::mt19937_64 rng(seed);
  std::vector<double> effects;
  effects.reserve(kResamples);
  std::vector<size_t> drawn(runs);
  for (int i = 0; i < kResamples; ++i) {
    for (size_t& r : drawn) r = draw(rng, runs);
    double sums[2] = {0.0, 0.0};
    for (int s = 0; s < 2; ++s) {
      const std::vector<RunSamples>& side = s == 0 ? first : second;
      for (const RunSamples& item : side) sums[s] += resampled_item_mean(item, drawn, rng);
      sums[s] /= double(side.size());
    }
    effects.push_back(ratio && sums[1] == 0.0 ? effect_of(a, b, ratio)
                                              : effect_of(sums[0], sums[1], ratio));
  }
  return percentile_interval(effect_of(a, b, ratio), ratio, std::move(effects));
}

EffectInterval paired_bootstrap(const std::vector<PointErrors>& first,
                                const std::vector<PointErrors>& second,
                                const std::string& statistic, uint64_t seed) {
  // Point count per group (the smallest, should items of a group disagree).
  std::map<std::string, size_t> points;
  for (const auto* side : {&first, &second})
    for (const PointErrors& item : *side) {
      const size_t n = item.errors->size();
      auto [it, added] = points.emplace(item.group, n);
      if (!added) it->second = std::min(it->second, n);
    }
  std::map<std::string, std::vector<size_t>> indices;
  for (const auto& [group, n] : points) {
    std::vector<size_t>& all = indices[group];
    for (size_t k = 0; k < n; ++k) all.push_back(k);
  }
  std::vector<double> values;
  const auto side_value = [&](const std::vector<PointErrors>& side) {
    double sum = 0.0;
    for (const PointErrors& item : side) {
      values.clear();
      for (size_t k : indices[item.group]) values.push_back(std::abs((*item.errors)[k]));
      sum += statistic_of(values, statistic);
    }
    return sum / double(side.size());
  };
  const double effect = side_value(first) - side_value(second);
  std::mt19937_64 rng(seed);
  std::vector<double> effects;
  effects.reserve(kResamples);
  for (int i = 0; i < kResamples; ++i) {
    for (auto& [group, drawn] : indices)
      for (size_t& k : drawn) k = draw(rng, points[group]);
    effects.push_back(side_value(first) - side_value(second));
  }
  return percentile_interval(effect, false, std::move(effects));
}

uint64_t seed_of(const std::string& text) {
  uint64_t h = 1469598103934665603ull;
  for (unsigned char c : text) h = (h ^ c) * 1099511628211ull;
  return h;
}

}  // namespace dv
