// `deepvox info SCENE [--json]`: what a scene holds (objects, triangles, volumes, lights, bounds).
#include <cstdio>
#include <iostream>

#include <nlohmann/json.hpp>

#include "apps/deepvox/commands.h"
#include "io/scene_loader.h"
#include "scene/scene.h"

namespace dv::cli {

namespace {

nlohmann::json vec(const dvec3& v) {
  return {v.x, v.y, v.z};
}

nlohmann::json describe(const Scene& scene) {
  nlohmann::json j;
  int64_t triangles = 0;
  j["objects"] = nlohmann::json::array();
  for (const Object& o : scene.objects) {
    const TriangleMesh& m = scene.meshes[o.mesh];
    triangles += int64_t(m.triangles.size());
    nlohmann::json obj = {{"name", o.name},
                          {"mesh", m.name},
                          {"triangles", m.triangles.size()},
                          {"alpha", o.material.alpha},
                          {"interior", to_string(o.interior.kind)}};
    if (o.interior.kind == InteriorKind::constant) obj["sigma"] = o.interior.sigma;
    if (o.interior.kind == InteriorKind::volume)
      obj["volume"] = scene.volumes[o.interior.volume].name;
    j["objects"].push_back(obj);
  }
  j["triangles"] = triangles;
  j["volumes"] = nlohmann::json::array();
  for (const VolumeGrid& v : scene.volumes)
    j["volumes"].push_back({{"name", v.name},
                            {"dims", {v.dims.x, v.dims.y, v.dims.z}},
                            {"spacing", vec(v.spacing)},
                            {"origin", vec(v.origin)}});
  j["lights"] = nlohmann::json::array();
  for (const Light& l : scene.lights) {
    nlohmann::json light = {{"type", to_string(l.type)}, {"intensity", l.intensity}};
    if (l.type != LightType::directional) light["position"] = vec(l.position);
    if (l.type != LightType::omni) light["direction"] = vec(l.direction);
    if (l.type == LightType::spot) light["cutoff"] = l.cutoff_deg;
    j["lights"].push_back(light);
  }
  const Aabb b = world_bounds(scene);
  j["bounds"] = {{"min", vec(b.lo)}, {"max", vec(b.hi)}};
  j["camera"] = {{"position", vec(scene.camera.position)},
                 {"target", vec(scene.camera.target)},
                 {"fov", scene.camera.fov_deg},
                 {"width", scene.camera.width},
                 {"height", scene.camera.height}};
  return j;
}

}  // namespace

Runner add_info(CLI::App& app) {
  struct Options {
    std::string scene;
    bool json = false;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* cmd =
      app.add_subcommand("info", "objects, triangles, volumes, lights and bounds of a scene");
  cmd->add_option("scene", opt->scene, "scene: .json, .gltf/.glb or a mesh file")->required();
  cmd->add_flag("--json", opt->json, "print JSON instead of text");
  return [opt] {
    const Scene scene = load_scene(opt->scene);
    const nlohmann::json j = describe(scene);
    if (opt->json) {
      std::cout << j.dump(2) << "\n";
      return 0;
    }
    std::printf("scene     %s\n", opt->scene.c_str());
    std::printf("objects   %zu (%lld triangles)\n", scene.objects.size(),
                (long long)j["triangles"].get<int64_t>());
    for (const auto& o : j["objects"])
      std::printf("  %-20s %8lld triangles  alpha %.3g  interior %s\n",
                  o["name"].get<std::string>().c_str(), (long long)o["triangles"].get<int64_t>(),
                  o["alpha"].get<double>(), o["interior"].get<std::string>().c_str());
    std::printf("volumes   %zu\n", scene.volumes.size());
    for (const VolumeGrid& v : scene.volumes)
      std::printf("  %-20s %d x %d x %d\n", v.name.c_str(), v.dims.x, v.dims.y, v.dims.z);
    std::printf("lights    %zu\n", scene.lights.size());
    for (const auto& l : j["lights"]) std::printf("  %s\n", l.dump().c_str());
    std::printf("bounds    %s\n", j["bounds"].dump().c_str());
    std::printf("camera    %s\n", j["camera"].dump().c_str());
    return 0;
  };
}

}  // namespace dv::cli
