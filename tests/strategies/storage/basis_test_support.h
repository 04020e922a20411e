// What the tests of the storages that fold a texel into a fixed record (moments, fourier,
// occupancy) share: a texel's record filled from a node list the way the storages' two passes
// fill it, a lookup over it by storage name, and analytic depth profiles (constant-extinction
// slabs and translucent surfaces) with their exact transmittance and nodes.
#pragma once

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "strategies/storage/fourier_device.h"
#include "strategies/storage/moments_device.h"
#include "strategies/storage/occupancy_device.h"

namespace dv::test {

using Nodes = std::vector<std::pair<float, float>>;  // (z, v) as the compressor emits them

// One texel's record filled from `nodes` the way the storages' two passes fill it.
template <class Sink>
std::vector<float> texel_record(const Nodes& nodes, Sink sink, int stride) {
  std::vector<float> record(stride, 0.0f);
  DepthRangeSink range;
  for (const auto& [z, v] : nodes) range.emit(z, v);
  record[0] = range.first, record[1] = range.last;
  sink.texel = record.data();
  for (const auto& [z, v] : nodes) sink.emit(z, v);
  sink.write();
  return record;
}

// Slabs of the occupancy texels these tests build (the storage's default).
inline constexpr int kOccupancyTestSlabs = 4;

// A lookup function over one texel for `storage` ("moments4", "moments6", "fourierK",
// "occupancyS": S slices in kOccupancyTestSlabs slabs).
struct BasisTexel {
  std::string storage;
  std::vector<float> record;

  BasisTexel(const std::string& name, const Nodes& nodes) : storage(name) {
    if (is("moments"))
      record = texel_record(nodes, PowerMomentSink{nullptr, order()}, moments_stride(order()));
    else if (is("fourier"))
      record = texel_record(nodes, FourierSink{nullptr, order()}, fourier_stride(order()));
    else
      record = texel_record(nodes, OccupancySink{nullptr, order(), kOccupancyTestSlabs},
                            occupancy_stride(order(), kOccupancyTestSlabs));
  }
  bool is(const char* kind) const { return storage.rfind(kind, 0) == 0; }
  // Moments, frequencies or slices: the number after the storage's name.
  int order() const { return std::stoi(storage.substr(storage.find_first_of("0123456789"))); }
  double at(float z) const {
    int hint = -1;
    const View<const float> data{record.data(), int64_t(record.size())};
    if (is("moments")) {
      const MomentsReader r{data, order(), float(default_moment_bias(order())), 0.25f};
      return r.visibility(0, z, hint);
    }
    if (is("fourier")) return FourierReader{data, order()}.visibility(0, z, hint);
    return OccupancyReader{data, order(), kOccupancyTestSlabs}.visibility(0, z, hint);
  }
};

// Nodes of constant-extinction slabs [a, b] (extinction sigma), sampled exactly every `step`,
// and translucent surfaces (z, alpha), in depth order.
struct Profile {
  struct Slab {
    double a, b, sigma;
  };
  std::vector<Slab> slabs;
  std::vector<std::pair<double, double>> surfaces;  // (z, alpha)

  double optical_depth(double z) const {
    double tau = 0.0;
    for (const Slab& s : slabs) tau += s.sigma * std::clamp(z - s.a, 0.0, s.b - s.a);
    for (const auto& [zs, alpha] : surfaces)
      if (zs < z) tau -= std::log(1.0 - alpha);
    return tau;
  }
  double transmittance(double z) const { return std::exp(-optical_depth(z)); }

  Nodes nodes(double step) const {
    std::vector<double> depths;
    for (const Slab& s : slabs)
      for (double z = s.a; z < s.b + 0.5 * step; z += step) depths.push_back(std::min(z, s.b));
    for (const auto& [zs, alpha] : surfaces) depths.push_back(zs);
    std::sort(depths.begin(), depths.end());
    Nodes out;
    for (double z : depths) {
      const bool surface = std::any_of(surfaces.begin(), surfaces.end(),
                                       [&](const auto& s) { return s.first == z; });
      if (surface) out.push_back({float(z), float(transmittance(z))});
      out.push_back({float(z), float(transmittance(std::nextafter(z, 1e300)))});
    }
    return out;
  }
};

// Depth ranges of the extreme texels: ordinary, 10 decades wide, far from the light, and of
// zero width.
inline const std::vector<std::pair<double, double>> kExtremeRanges = {
    {1.0, 2.0}, {1e-3, 1e7}, {1e6, 1e6 + 0.25}, {5.0, 5.0}};

// 2000 translucent surfaces (alpha up to 0.02 each, drawn from `rng`) spread over [near, far].
inline Nodes many_surfaces(double near, double far, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Nodes nodes;
  double v = 1.0;
  for (int i = 0; i < 2000; ++i) {
    const float z = float(near + (far - near) * i / 1999.0);
    nodes.push_back({z, float(v)});
    v *= 1.0 - 0.02 * u(rng);
    nodes.push_back({z, float(v)});
  }
  return nodes;
}

struct ErrorFigures {
  double max = 0.0, mean = 0.0;
};

// |T' - T| over depths spread over [lo, hi].
inline ErrorFigures error_over(const BasisTexel& texel, const Profile& p, double lo, double hi) {
  ErrorFigures e;
  const int n = 400;
  for (int i = 0; i <= n; ++i) {
    const double z = lo + (hi - lo) * i / n;
    const double d = std::abs(texel.at(float(z)) - p.transmittance(double(float(z))));
    e.max = std::max(e.max, d);
    e.mean += d / (n + 1);
  }
  return e;
}

}  // namespace dv::test
