// Shared pieces of the hard-case suite (`ctest -L hard`, tests/CMakeLists.txt): tests
// parameterised over the backends that skip with their reason where no GPU is present, deep
// shadow maps generated on a backend, and DSM lookups run there (a kernel on CUDA) for plain
// receivers (points that are not on a surface: no bias).
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "cuda/device_memory.h"
#include "cuda/execute.h"
#include "strategies/storage/deep_shadow_maps.h"
#include "tests/support/scene_builder.h"

namespace dv::test {

class HardOnBackends : public ::testing::TestWithParam<Backend> {
 protected:
  void SetUp() override {
    std::string why;
    if (GetParam() == Backend::cuda && !cuda_device_available(&why))
      GTEST_SKIP() << "the CUDA run of this hard case needs a GPU: " << why;
  }
};

struct BackendName {
  std::string operator()(const ::testing::TestParamInfo<Backend>& info) const {
    return to_string(info.param);
  }
};

// A scene flattened into the backend's memory with its deep shadow maps.
struct HardMaps {
  std::unique_ptr<SceneData> data;
  std::unique_ptr<DeepShadowMaps> maps;
};

inline DsmSettings unbiased_settings(float eps, int res, bool bilinear = false) {
  DsmSettings s;
  s.resolution = res;
  s.eps = eps;
  s.bias = 0.0;
  s.slope_bias = 0.0;
  s.bilinear = bilinear;
  return s;
}

inline HardMaps generate_maps(Scene scene, Backend backend, const DsmSettings& settings) {
  validate_scene(scene);
  HardMaps m;
  m.data = std::make_unique<SceneData>(scene, memory_of(backend));
  m.maps = std::make_unique<DeepShadowMaps>(settings);
  m.maps->generate(*m.data, backend);
  return m;
}

// The maps' transmittance of `light` at each point, computed on the maps' backend.
inline std::vector<double> dsm_lookups(const HardMaps& m, Backend backend,
                                       const std::vector<dvec3>& points, int light) {
  const Buffer<dvec3> in(memory_of(backend), std::span<const dvec3>(points), "points");
  Buffer<double> out(memory_of(backend), int64_t(points.size()), "transmittance");
  const DsmSource source = m.maps->source();
  const View<const dvec3> p = in.const_view();
  const View<double> o = out.view();
  parallel_for(
      backend, "hard_dsm_lookups", int64_t(points.size()), DV_KERNEL_LAMBDA(int64_t i) {
        DsmSource::Cursor cursor;
        o[i] = source.transmittance(cursor, ShadowReceiver{p[i]}, light);
      });
  return out.to_vector();
}

// A square translucent quad of side `size` in the plane y = height, centred on the y axis.
inline TriangleMesh quad_at(double height, double size) {
  TriangleMesh q = make_quad(size);
  for (dvec3& v : q.positions) v.y = height;
  return q;
}

}  // namespace dv::test
