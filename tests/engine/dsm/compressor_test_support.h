// Shared pieces of the visibility-compressor tests: a host sink collecting nodes, an independent
// double-precision evaluator of piecewise-linear visibility functions with steps (left and right
// limits), the dense error check the guarantee is stated in, and random texels (smoke-like
// volumes with surface steps, coincident surfaces, zero-length gaps and flat runs).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "engine/dsm/visibility_compressor.h"

namespace dv::test {

struct Node {
  float z = 0.0f;
  float v = 1.0f;
};
using Samples = std::vector<Node>;  // the input stream in push order; a step is two at one z

struct VectorSink {
  std::vector<Node>* nodes = nullptr;
  bool emit(float z, float v) {
    nodes->push_back({z, v});
    return true;
  }
};

struct Compressed {
  std::vector<Node> nodes;
  VisibilityCompressionStats stats;
};

inline Compressed compress(const Samples& samples, float eps) {
  Compressed out;
  VisibilityCompressor<VectorSink> compressor(eps, VectorSink{&out.nodes});
  for (const Node& s : samples) compressor.push(s.z, s.v);
  compressor.finish();
  out.stats = compressor.stats();
  return out;
}

// Value of the function through `nodes` just before z (left) or just after z (right): 1 before
// the first node, the last value after the last, linear in between, steps at shared depths.
inline double evaluate(const std::vector<Node>& nodes, double z, bool right) {
  const auto first_after = [&](bool or_equal) {
    return std::partition_point(nodes.begin(), nodes.end(), [&](const Node& n) {
      return or_equal ? double(n.z) < z : double(n.z) <= z;
    });
  };
  const auto next = first_after(!right);  // left: first node at or after z; right: after z
  if (next == nodes.begin()) return 1.0;
  if (next == nodes.end()) return nodes.back().v;
  if (!right && double(next->z) == z) return next->v;
  const Node& a = *(next - 1);
  const Node& b = *next;
  const double t = (z - double(a.z)) / (double(b.z) - double(a.z));
  return double(a.v) + (double(b.v) - double(a.v)) * t;
}

// max |V'(z) - V(z)| over both limits at every input depth, the midpoints between distinct
// depths, and before the first and after the last: the error is linear between those.
inline double max_error(const Samples& samples, const std::vector<Node>& nodes) {
  if (samples.empty()) return nodes.empty() ? 0.0 : 1.0;
  std::vector<double> depths;
  depths.push_back(double(samples.front().z) - 1.0);
  for (size_t i = 0; i < samples.size(); ++i) {
    depths.push_back(samples[i].z);
    if (i + 1 < samples.size() && samples[i + 1].z > samples[i].z)
      depths.push_back(0.5 * (double(samples[i].z) + double(samples[i + 1].z)));
  }
  depths.push_back(double(samples.back().z) + 1.0);
  double worst = 0.0;
  for (double z : depths)
    for (bool right : {false, true})
      worst = std::max(worst, std::abs(evaluate(nodes, z, right) - evaluate(samples, z, right)));
  return worst;
}

inline bool is_monotone(const std::vector<Node>& nodes) {
  float z = -INFINITY, v = 1.0f;
  for (const Node& n : nodes) {
    if (!(n.z >= z) || !(n.v <= v) || !(n.v >= 0.0f)) return false;
    z = n.z, v = n.v;
  }
  return true;
}

// One texel's walk through a random scene: flat gaps, smoke-like volumes (exp of cumulative
// random positive densities) and surface crossings, some coincident, some opaque.
inline Samples random_texel(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Samples out;
  const double z_origin = u(rng) < 0.15 ? 2000.0 + 8000.0 * u(rng) : 0.5 + 50.0 * u(rng);
  double z = z_origin, t = 1.0;
  const int count = 1 + int(std::pow(u(rng), 1.5) * 400.0);
  const double step = std::exp(std::log(1e-3) + u(rng) * std::log(500.0));  // 1e-3 .. 0.5
  const double scale = std::exp(std::log(0.01) + u(rng) * std::log(3000.0)) / step / count;
  double density = 0.0;
  bool in_volume = u(rng) < 0.7;
  auto sample = [&] { out.push_back({float(z), float(t)}); };
  sample();
  while (int(out.size()) < count) {
    if (u(rng) < 0.02) in_volume = !in_volume;
    if (u(rng) < 0.03) {  // a surface crossing, sometimes several at one depth
      for (int k = 0; k == 0 || u(rng) < 0.3; ++k) {
        const double r = u(rng);
        const double alpha = r < 0.1 ? 1.0 : (r < 0.3 ? 1e-4 * u(rng) : u(rng));
        out.push_back({float(z), float(t)});
        t *= 1.0 - alpha;
        out.push_back({float(z), float(t)});
      }
    }
    if (u(rng) < 0.05) {  // a zero-length gap: the same depth again
      sample();
      continue;
    }
    const double dz = step * (u(rng) < 0.1 ? 1e-3 : 0.5 + u(rng));
    density = std::max(0.0, density + scale * (u(rng) - 0.5));
    if (u(rng) < 0.05) density = scale * 4.0 * u(rng);
    z += dz;
    if (in_volume) t *= std::exp(-density * dz);
    sample();
  }
  return out;
}

// A texel through a smoke plume: entry at the first fragment, a smooth positive density of
// a few octaves along the ray, optical depth of order one over a few hundred samples.
inline Samples smoke_texel(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int count = 128 + int(u(rng) * 384.0);
  const double step = 0.02, z0 = 5.0 + 10.0 * u(rng), depth = 0.3 + 4.0 * u(rng);
  double phase[3], octave_weight = 0.0;
  for (double& p : phase) p = 6.2831853 * u(rng);
  std::vector<double> density(count);
  for (int i = 0; i < count; ++i) {
    const double x = double(i) / count;
    double d = 0.0, w = 1.0, f = 3.0;
    for (double p : phase)
      d += w * std::max(0.0, std::sin(f * x * 6.2831853 + p)), w *= 0.5, f *= 2.3;
    density[i] = d * d;
    octave_weight += density[i];
  }
  Samples out;
  double t = 1.0;
  for (int i = 0; i < count; ++i) {
    if (i > 0) t *= std::exp(-depth * density[i] / octave_weight);
    out.push_back({float(z0 + step * i), float(t)});
  }
  return out;
}

}  // namespace dv::test
