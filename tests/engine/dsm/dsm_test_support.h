// Shared pieces of the deep-shadow-map tests: scenes (the repository's scene files and random
// scenes of translucent boxes, spheres and constant media built in code), a generation target
// that records the walk's raw samples beside the compressor's nodes, and texel-centre points.
#pragma once

#include <random>
#include <string>
#include <vector>

#include "cuda/buffer.h"
#include "cuda/execute.h"
#include "engine/dsm/dsm_generation.h"
#include "experiments/source_paths.h"
#include "render/load/mesh_generators.h"
#include "render/load/scene_loader.h"
#include "strategies/storage/deep_shadow_maps.h"
#include "tests/engine/dsm/compressor_test_support.h"
#include "tests/support/scene_builder.h"

namespace dv::test {

inline Scene scene_file(const std::string& name) {
  return load_scene(source_dir() + "/experiments/scenes/" + name);
}

// Translucent boxes and spheres, some with constant media, lit by a spot and an omni light.
inline Scene random_scene(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  SceneBuilder b;
  for (int i = 0; i < 10; ++i) {
    const dvec3 c(u(rng) * 4 - 2, u(rng) * 2, u(rng) * 4 - 2);
    const double r = 0.3 + 0.7 * u(rng);
    const double alpha = u(rng) < 0.15 ? 1.0 : 0.1 + 0.6 * u(rng);
    const bool medium = u(rng) < 0.5;
    TriangleMesh mesh = u(rng) < 0.5 ? make_box(c - dvec3(r), c + dvec3(r)) : [&] {
      TriangleMesh m = make_icosphere(r, 2);
      for (dvec3& v : m.positions) v += c;
      return m;
    }();
    b.add(std::move(mesh), alpha, medium ? InteriorKind::constant : InteriorKind::none,
          medium ? 0.5 + 2.0 * u(rng) : 0.0);
  }
  b.spot(dvec3(0.3, 6.0, 0.2), dvec3(0.0, -1.0, 0.05), 40.0);
  b.omni(dvec3(-3.5, 3.0, 3.0));
  validate_scene(b.scene);
  return b.scene;
}

// Forwards the walk to the compressor and keeps the raw samples it saw.
struct RecordingTarget {
  Samples samples;
  std::vector<Node> nodes;
  VisibilityCompressor<VectorSink> compressor;
  explicit RecordingTarget(float eps) : compressor(eps, VectorSink{&nodes}) {}
  void push(float z, float v) {
    samples.push_back({z, v});
    compressor.push(z, v);
  }
  void push_step(float z, float before, float after) {
    push(z, before);
    push(z, after);
  }
};

}  // namespace dv::test
