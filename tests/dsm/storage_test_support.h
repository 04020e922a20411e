// Shared pieces of the storage tests: generating a scene's maps into a storage chosen by name on
// a backend, and reading every texel's V' at a fixed set of depths through the storage's reader
// (on that backend), for comparisons between storages, backends and the oracle.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "dsm/deep_shadow_maps.h"
#include "tests/dsm/dsm_test_support.h"

namespace dv::test {

struct Generated {
  std::unique_ptr<SceneData> data;
  std::unique_ptr<DeepShadowMaps> maps;
};

inline Generated generate(const Scene& scene, Backend backend, const std::string& storage,
                          const std::vector<std::string>& params = {}, float eps = 0.02f,
                          int res = 32) {
  DsmSettings s;
  s.storage = storage;
  s.storage_params = StrategyParams::parse(params);
  s.resolution = res;
  s.eps = eps;
  Generated g;
  g.data = std::make_unique<SceneData>(scene, memory_of(backend));
  g.maps = std::make_unique<DeepShadowMaps>(s);
  g.maps->generate(*g.data, backend);
  return g;
}

// V' of every texel at kLookupDepths depths, texel-major (texel_lookups).
inline std::vector<float> sample_lookups(const Generated& g, Backend backend) {
  return texel_lookups(*g.maps, *g.data, backend);
}

// Every lookup of a and b agrees within 1e-6.
inline void expect_same_lookups(const Generated& a, const Generated& b, Backend backend) {
  const std::vector<float> va = sample_lookups(a, backend), vb = sample_lookups(b, backend);
  ASSERT_EQ(va.size(), vb.size());
  int64_t differing = 0;
  for (size_t i = 0; i < va.size(); ++i) differing += std::abs(va[i] - vb[i]) > 1e-6f;
  EXPECT_EQ(differing, 0);
}

}  // namespace dv::test
