// Small scenes for tests, built in code: objects from generators with a material and interior,
// lights, a helper that validates and flattens them for the CPU backend, and oracle queries.
#pragma once

#include <gtest/gtest.h>

#include <utility>

#include "engine/oracle/transmittance.h"
#include "engine/scene/scene.h"
#include "engine/scene/scene_view.h"
#include "render/load/mesh_generators.h"

namespace dv::test {

struct SceneBuilder {
  Scene scene;

  SceneBuilder() { scene.source = "test-scene"; }

  Object& add(TriangleMesh mesh, double alpha = 1.0, InteriorKind kind = InteriorKind::none,
              double sigma = 0.0) {
    scene.meshes.push_back(std::move(mesh));
    Object o;
    o.name = "object" + std::to_string(scene.objects.size());
    o.mesh = int(scene.meshes.size()) - 1;
    o.material.alpha = alpha;
    o.interior.kind = kind;
    o.interior.sigma = sigma;
    scene.objects.push_back(o);
    return scene.objects.back();
  }

  Light& omni(const dvec3& position) {
    Light l;
    l.type = LightType::omni;
    l.position = position;
    scene.lights.push_back(l);
    return scene.lights.back();
  }

  Light& spot(const dvec3& position, const dvec3& direction, double cutoff_deg) {
    Light l;
    l.type = LightType::spot;
    l.position = position;
    l.direction = direction;
    l.cutoff_deg = cutoff_deg;
    scene.lights.push_back(l);
    return scene.lights.back();
  }

  Light& directional(const dvec3& direction) {
    Light l;
    l.type = LightType::directional;
    l.direction = direction;
    scene.lights.push_back(l);
    return scene.lights.back();
  }

  // Validates (orients interiors outward) and flattens into host memory.
  SceneData build() {
    validate_scene(scene);
    return SceneData(scene, Memory::host);
  }
};

// The oracle's transmittance of `light` at p; a raised flag fails the calling test.
inline double oracle_at(const SceneData& data, int light, const dvec3& p) {
  const OracleResult r = exact_transmittance(data.view(), data.view().lights[light], p);
  EXPECT_EQ(r.flags, 0u);
  return r.transmittance;
}

}  // namespace dv::test
