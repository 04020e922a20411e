// A tinted caster over grey translucent layers, built here: a blue glass pane (transmission 1)
// over a grey translucent slab (alpha 0.5) over an opaque floor, under a spot light (the
// smallest form of TransmissionTest's translucent cloth under its glass bodies). The grey layer
// behind the tint must not dilute the tint in front of it (a side channel with one exponent per
// texel summed to the floor would mix the slab's grey into the glass's blue just above the
// slab), and the layers behind the tint must scale every channel alike. Just above the grey
// slab and on the floor every dsm storage and auto keep the oracle's colour (each channel over
// the luminance within 5 % of the oracle's), and auto and the storages that keep their error
// bound answer within 0.05 of the oracle per channel. The fixed-size storages' own luminance
// error on this stack of layers is theirs, not the colour's (printed); `beer` is held to blue
// only (its one curve misses a translucent layer over an opaque receiver, docs/rendering.md).
// On CPU and CUDA.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "cuda/buffer.h"
#include "engine/scene/surface_transmittance.h"
#include "render/load/mesh_generators.h"
#include "strategies/shadow/probe.h"
#include "strategies/storage/dsm_storage.h"
#include "tests/support/backends.h"
#include "tests/support/shadow_methods.h"

namespace dv {
namespace {

Scene blue_pane_over_grey_slab() {
  Scene scene;
  scene.source = "tint-over-grey-layers";
  scene.meshes.push_back(make_box({-3.0, -0.05, -3.0}, {3.0, 0.0, 3.0}));
  scene.meshes.push_back(make_box({-0.6, 1.0, -0.6}, {0.6, 1.05, 0.6}));
  scene.meshes.push_back(make_box({-1.0, 0.5, -1.0}, {1.0, 0.52, 1.0}));
  Object floor;
  floor.name = "floor";
  floor.mesh = 0;
  floor.material.color = dvec3(0.9);
  scene.objects.push_back(floor);
  Object glass;
  glass.name = "blue glass pane";
  glass.mesh = 1;
  glass.material.color = {0.3, 0.45, 1.0};
  glass.material.alpha = 0.0;
  glass.material.transmission = 1.0;
  scene.objects.push_back(glass);
  Object grey;
  grey.name = "grey translucent slab";
  grey.mesh = 2;
  grey.material.color = dvec3(0.8);
  grey.material.alpha = 0.5;
  scene.objects.push_back(grey);
  Light spot;
  spot.position = {0.1, 4.0, 0.05};
  spot.direction = {0.0, -1.0, 0.0};
  spot.cutoff_deg = 35.0;
  spot.penumbra_deg = 3.0;
  spot.intensity = 12.0;
  scene.lights.push_back(spot);
  validate_scene(scene);
  return scene;
}

// Points at height y whose light path crosses the pane's middle.
std::vector<dvec3> points_at(double y) {
  std::vector<dvec3> points;
  for (int i = -2; i <= 2; ++i)
    for (int j = -1; j <= 1; ++j) points.push_back({0.15 * i, y, 0.15 * j});
  return points;
}

class TintOverGreyLayers : public ::testing::TestWithParam<Backend> {};

TEST_P(TintOverGreyLayers, GreyLayersBehindTheTintNeitherDiluteNorTintIt) {
  DV_SKIP_UNLESS_BACKEND(GetParam());
  const Backend backend = GetParam();
  const SceneData data(blue_pane_over_grey_slab(), memory_of(backend));
  auto reference = test::make_shadow_method("reference", "");
  struct Method {
    std::string name, params;
    bool bounded;  // keeps its error bound: held within 0.05 per channel
  };
  std::vector<Method> methods = {{"auto", "", true}};
  for (const std::string& storage : storage_registry().names())
    methods.push_back(
        {"dsm", "storage=" + storage, storage_registry().create(storage)->keeps_error_bound()});
  for (const double y : {0.53, 0.0}) {  // above the grey slab (glass only), on the floor (both)
    const std::vector<dvec3> points = points_at(y);
    const ProbeResults exact = probe_transmittance(backend, data, *reference, points);
    for (const dvec3& t : exact.rgb) {
      EXPECT_GT(t.z, 2.0 * t.x) << "the oracle's shadow is blue at y " << y;
      EXPECT_GT(t.z, 0.15) << y;
    }
    for (const Method& m : methods) {
      auto method = test::make_shadow_method(m.name, m.params);
      const ProbeResults r = probe_transmittance(backend, data, *method, points);
      double luminance_error = 0.0;
      for (size_t i = 0; i < points.size(); ++i) {
        const dvec3& t = r.rgb[i];
        const std::string where =
            m.name + " " + m.params + " y " + std::to_string(y) + " point " + std::to_string(i);
        EXPECT_GT(t.z, 1.5 * t.x) << where << ": not blue";
        luminance_error =
            std::max(luminance_error, std::abs(luminance(t) - luminance(exact.rgb[i])));
        if (m.params == "storage=beer") continue;
        for (int c = 0; c < 3; ++c) {
          const double colour = t[c] / luminance(t),
                       exact_colour = exact.rgb[i][c] / luminance(exact.rgb[i]);
          EXPECT_NEAR(colour, exact_colour, 0.05 * exact_colour) << where << " channel " << c;
          if (m.bounded) {
            EXPECT_NEAR(t[c], exact.rgb[i][c], 0.05) << where << " channel " << c;
          }
        }
      }
      std::cout << m.name << " " << m.params << " at y " << y << ": largest luminance error "
                << luminance_error << "\n";
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, TintOverGreyLayers, ::testing::ValuesIn(test::all_backends()),
                         [](const ::testing::TestParamInfo<Backend>& info) {
                           return std::string(info.param == Backend::cuda ? "cuda" : "cpu");
                         });

}  // namespace
}  // namespace dv
