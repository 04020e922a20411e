// Intervals of effect sizes (effect_interval.h): Student-t over per-run effects, and a paired
// bootstrap over probe points whose indices are drawn as rng() % n from mt19937_64 (no std
// distributions), so the same seed gives the same interval everywhere.
#include "experiments/harness/effect_interval.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

#include "experiments/harness/student_t.h"

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

EffectInterval percentile_interval(double effect, bool ratio, std::vector<double> resampled) {
  std::sort(resampled.begin(), resampled.end());
  const auto at = [&](double q) {
    const size_t i = size_t(std::floor(q * double(resampled.size() - 1) + 0.5));
    return resampled[std::min(i, resampled.size() - 1)];
  };
  return {effect, at(0.025), at(0.975), ratio};
}

// An item's mean sample in run `r`, or NaN where it was not measured in that run.
double item_run_mean(const RunSamples& item, size_t r) {
  if (r >= item.size() || item[r].empty()) return std::nan("");
  return mean_of(item[r]);
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

EffectInterval t_interval(const std::vector<double>& per_run_effects, bool ratio) {
  std::vector<double> x;
  for (double e : per_run_effects) x.push_back(ratio ? std::log(e) : e);
  const double n = double(x.size());
  const double mean = mean_of(x);
  double squares = 0.0;
  for (double v : x) squares += (v - mean) * (v - mean);
  const double half = student_t_quantile(0.975, n - 1.0) * std::sqrt(squares / (n - 1.0) / n);
  if (ratio) return {std::exp(mean), std::exp(mean - half), std::exp(mean + half), true};
  return {mean, mean - half, mean + half, false};
}

RunInterval run_interval(const std::vector<RunSamples>& first,
                         const std::vector<RunSamples>& second, bool difference) {
  size_t runs = 0;
  for (const auto* side : {&first, &second})
    for (const RunSamples& item : *side) runs = std::max(runs, item.size());
  // Per run in which every item of both sides was measured: the two sides' means.
  std::vector<double> means[2];
  for (size_t r = 0; r < runs; ++r) {
    double sums[2] = {0.0, 0.0};
    bool complete = true;
    for (int s = 0; s < 2 && complete; ++s) {
      const std::vector<RunSamples>& side = s == 0 ? first : second;
      for (const RunSamples& item : side) {
        const double m = item_run_mean(item, r);
        complete &= !std::isnan(m);
        sums[s] += m;
      }
      sums[s] /= double(side.size());
    }
    if (!complete) continue;
    means[0].push_back(sums[0]);
    means[1].push_back(sums[1]);
  }
  RunInterval out;
  out.runs = means[0].size();
  if (out.runs < 2) return out;
  bool ratio = !difference;
  for (size_t r = 0; r < out.runs; ++r) ratio &= means[0][r] > 0.0 && means[1][r] > 0.0;
  std::vector<double> effects;
  for (size_t r = 0; r < out.runs; ++r)
    effects.push_back(ratio ? means[0][r] / means[1][r] : means[0][r] - means[1][r]);
  out.interval = t_interval(effects, ratio);
  return out;
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
