// Shared pieces of the storage tests: generating a scene's maps into a storage chosen by name on
// a backend, and reading every texel's V' at a fixed set of depths through the storage's reader
// (on that backend), for comparisons between storages, backends and the oracle. Launches
// kernels: include it only from files nvcc compiles (deepvox_kernel_sources).
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "strategies/storage/deep_shadow_maps.h"
#include "tests/engine/dsm/dsm_test_support.h"

namespace dv::test {

inline constexpr int kLookupDepths = 24;

// Visibility of every texel of `maps` at kLookupDepths depths from 0 to twice the scene
// diagonal, texel-major, through the storage's reader on `backend` (where the maps live), copied
// to the host.
inline std::vector<float> texel_lookups(const DeepShadowMaps& maps, const SceneData& data,
                                        Backend backend) {
  const DsmSource source = maps.source();
  const int64_t texels = int64_t(maps.records().size());
  const int depths = kLookupDepths;
  Buffer<float> out(memory_of(backend), texels * depths, "lookups");
  const View<float> o = out.view();
  const double far = 2.0 * data.view().diagonal;
  parallel_for(
      backend, "test_dsm_lookups", texels * depths, DV_KERNEL_LAMBDA(int64_t i) {
        int hint = -1;
        const float z = float(far * double(i % depths) / depths);
        o[i] = source.reader.visibility(i / depths, z, hint);
      });
  return out.to_vector();
}

struct Generated {
  std::unique_ptr<SceneData> data;
  std::unique_ptr<DeepShadowMaps> maps;
};

// Map settings for `storage` with its parameters, `res` texels per side and error bound `eps`.
inline DsmSettings storage_settings(const std::string& storage,
                                    const std::vector<std::string>& params, float eps, int res) {
  DsmSettings s;
  s.storage = storage;
  s.storage_params = StrategyParams::parse(params);
  s.resolution = res;
  s.eps = eps;
  return s;
}

inline Generated generate(const Scene& scene, Backend backend, const std::string& storage,
                          const std::vector<std::string>& params = {}, float eps = 0.02f,
                          int res = 32) {
  const DsmSettings s = storage_settings(storage, params, eps, res);
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
