// Generating a scene's deep shadow maps with a storage strategy chosen by name, and sampling
// every texel's stored function at fixed depths through the storage's reader on either backend:
// what the storage tests compare (strategy against compact, CPU against CUDA). The sampling
// runs a kernel, so the including test files are compiled by nvcc when CUDA is on.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/execute.h"
#include "dsm/deep_shadow_maps.h"

namespace dv::test {

struct GeneratedMaps {
  std::unique_ptr<SceneData> data;
  std::unique_ptr<DeepShadowMaps> maps;
};

inline GeneratedMaps generate_maps(const Scene& scene, Backend backend, const std::string& storage,
                                   const std::vector<std::string>& params = {}, float eps = 0.02f,
                                   int res = 32) {
  DsmSettings s;
  s.storage = storage;
  s.storage_params = StrategyParams::parse(params);
  s.resolution = res;
  s.eps = eps;
  GeneratedMaps g;
  g.data = std::make_unique<SceneData>(scene, memory_of(backend));
  g.maps = std::make_unique<DeepShadowMaps>(s);
  g.maps->generate(*g.data, backend);
  return g;
}

inline constexpr int kSampledDepths = 24;

// Visibility of every texel at kSampledDepths depths (0 to twice the scene diagonal) through
// the storage's reader on `backend`, copied to the host: texel t's at [t * kSampledDepths, ..).
inline std::vector<float> sample_lookups(const GeneratedMaps& g, Backend backend) {
  const DsmSource source = g.maps->source();
  const int64_t texels = int64_t(g.maps->records().size());
  const int depths = kSampledDepths;
  Buffer<float> out(memory_of(backend), texels * depths, "lookups");
  const View<float> o = out.view();
  const double far = 2.0 * g.data->view().diagonal;
  parallel_for(
      backend, "test_dsm_lookups", texels * depths, DV_KERNEL_LAMBDA(int64_t i) {
        int hint = -1;
        const float z = float(far * double(i % depths) / depths);
        o[i] = source.reader.visibility(i / depths, z, hint);
      });
  return out.to_vector();
}

}  // namespace dv::test
