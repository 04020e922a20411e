// Texture alpha in every shadow method on the committed cut-out stand-in
// (tests/data/textured/alpha_mask_quad.gltf, written by make_textured_standins.py): a MASK quad
// whose texture cuts its left half away, and a BLEND quad of factor 0.4 with the same texture,
// over a floor under a sun. Cut-out texels cast nothing and opaque texels a full shadow in the
// oracle and every method; the BLEND quad's opaque texels let 0.6 through in the oracle and the
// deep shadow maps (which store partial visibility), and a depth map casts it only at or above
// its opaque-alpha threshold.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "experiments/source_paths.h"
#include "render/load/gltf_import.h"
#include "strategies/shadow/probe.h"
#include "strategies/storage/dsm_storage.h"
#include "tests/support/shadow_methods.h"

namespace dv {
namespace {

Scene cut_out_scene() {
  return load_gltf_scene(test::source_dir() + "/tests/data/textured/alpha_mask_quad.gltf");
}

// Floor points under the quads' two halves (z across the quad, away from texel edges).
struct FloorPoints {
  std::vector<dvec3> mask_cut, mask_opaque, blend_cut, blend_opaque;
};

FloorPoints floor_points() {
  FloorPoints p;
  for (double z : {-0.3, 0.0, 0.3}) {
    p.mask_cut.push_back({-1.3, 0.0, z});
    p.mask_opaque.push_back({-0.7, 0.0, z});
    p.blend_cut.push_back({0.7, 0.0, z});
    p.blend_opaque.push_back({1.3, 0.0, z});
  }
  return p;
}

std::vector<double> probe(const SceneData& data, ShadowMethod& method,
                          const std::vector<dvec3>& points) {
  return probe_transmittance(Backend::cpu, data, method, points).transmittance;
}

void expect_all_near(const std::vector<double>& values, double expected, double tolerance,
                     const std::string& what) {
  for (size_t i = 0; i < values.size(); ++i)
    EXPECT_NEAR(values[i], expected, tolerance) << what << " point " << i;
}

TEST(TextureAlpha, OracleCutsMaskAndScalesBlend) {
  const Scene scene = cut_out_scene();
  ASSERT_EQ(scene.textures.size(), 1u);
  const SceneData data(scene, Memory::host);
  auto reference = shadow_registry().create("reference");
  const FloorPoints p = floor_points();
  expect_all_near(probe(data, *reference, p.mask_cut), 1.0, 1e-12, "mask cut-out");
  expect_all_near(probe(data, *reference, p.mask_opaque), 0.0, 1e-12, "mask opaque");
  expect_all_near(probe(data, *reference, p.blend_cut), 1.0, 1e-12, "blend cut-out");
  expect_all_near(probe(data, *reference, p.blend_opaque), 0.6, 1e-12, "blend opaque");
}

// Every registered method but "none": cut-out texels of the MASK quad cast nothing and its
// opaque texels a full shadow.
TEST(TextureAlpha, EveryMethodCutsMaskedTexels) {
  const SceneData data(cut_out_scene(), Memory::host);
  const FloorPoints p = floor_points();
  std::vector<std::pair<std::string, std::string>> methods;
  for (const std::string& name : shadow_registry().names())
    if (name != "none" && name != "dsm") methods.push_back({name, ""});
  for (const std::string& storage : storage_registry().names())
    methods.push_back({"dsm", "storage=" + storage});
  for (const auto& [name, params] : methods) {
    SCOPED_TRACE(name + " " + params);
    auto method = test::make_shadow_method(name, params);
    expect_all_near(probe(data, *method, p.mask_cut), 1.0, 0.05, "mask cut-out");
    expect_all_near(probe(data, *method, p.mask_opaque), 0.0, 0.05, "mask opaque");
  }
}

TEST(TextureAlpha, DeepShadowMapsKeepBlendCoverage) {
  const SceneData data(cut_out_scene(), Memory::host);
  const FloorPoints p = floor_points();
  auto dsm = test::make_shadow_method("dsm", "");
  expect_all_near(probe(data, *dsm, p.blend_cut), 1.0, 0.02, "blend cut-out");
  expect_all_near(probe(data, *dsm, p.blend_opaque), 0.6, 0.02, "blend opaque");
}

}  // namespace
}  // namespace dv
