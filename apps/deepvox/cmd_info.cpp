// `deepvox info`: what a scene holds (objects, triangles, volumes, lights with their colours and
// units, bounds) and warnings about what will not look as a user expects.
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "apps/deepvox/commands.h"
#include "core/number_text.h"
#include "engine/scene/scene.h"
#include "render/load/scene_loader.h"

namespace dv::cli {

namespace {

nlohmann::json vec(const dvec3& v) {
  return {v.x, v.y, v.z};
}

// Renderer units of a light's intensity (radiometric; see render/load/gltf_import.h).
const char* intensity_unit(LightType type) {
  return type == LightType::directional ? "W/m^2" : "W/sr";
}

nlohmann::json describe_light(const Light& l) {
  nlohmann::json light = {{"type", to_string(l.type)},
                          {"color", vec(l.color)},
                          {"intensity", l.intensity},
                          {"unit", intensity_unit(l.type)}};
  if (!l.source_unit.empty())
    light["source"] = {{"intensity", l.source_intensity}, {"unit", l.source_unit}};
  if (l.type != LightType::directional) light["position"] = vec(l.position);
  if (l.type != LightType::omni) light["direction"] = vec(l.direction);
  if (l.type == LightType::spot) light["cutoff"] = l.cutoff_deg;
  if (l.range > 0.0) light["range"] = l.range;
  return light;
}

// "'a'", "'a', 'b' and 'c'", "'a', 'b', 'c' and 4 more" (at most `shown` names).
std::string name_list(const std::vector<std::string>& names, size_t shown = 3) {
  std::string out;
  const size_t listed = std::min(names.size(), shown);
  for (size_t i = 0; i < listed; ++i) {
    if (i > 0) out += i + 1 == listed && names.size() == listed ? " and " : ", ";
    out += "'" + names[i] + "'";
  }
  if (names.size() > listed) out += " and " + std::to_string(names.size() - listed) + " more";
  return out;
}

// What renders differently from what a user of the source file would expect: one line per
// kind of surprise, naming the objects it concerns (a model of many glass parts gets one line).
nlohmann::json warnings(const Scene& scene) {
  nlohmann::json out = nlohmann::json::array();
  std::vector<std::string> glass;
  for (const Object& o : scene.objects)
    if (o.material.alpha == 0.0 && o.material.transmission > 0.0) glass.push_back(o.name);
  if (!glass.empty())
    out.push_back(
        (glass.size() == 1
             ? "object " + name_list(glass) + " is"
             : std::to_string(glass.size()) + " objects (" + name_list(glass) + ") are") +
        " fully transmissive (glTF transmission 1): each casts the faint shadow its Fresnel "
        "reflectance and its colour leave, not a solid one; the camera sees its highlights, a "
        "Fresnel rim and its colour's tint on what is behind it");
  return out;
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
    if (o.material.transmission > 0.0) obj["transmission"] = o.material.transmission;
    if (o.interior.kind == InteriorKind::constant) {
      obj["sigma"] = o.interior.sigma;
      obj["sigma_rgb"] = vec(o.interior.sigma * o.interior.sigma_tint);
    }
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
  for (const Light& l : scene.lights) j["lights"].push_back(describe_light(l));
  const Aabb b = world_bounds(scene);
  j["bounds"] = {{"min", vec(b.lo)}, {"max", vec(b.hi)}};
  j["camera"] = {{"position", vec(scene.camera.position)},
                 {"target", vec(scene.camera.target)},
                 {"fov", scene.camera.fov_deg},
                 {"width", scene.camera.width},
                 {"height", scene.camera.height}};
  j["warnings"] = warnings(scene);
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
    for (const auto& o : j["objects"]) {
      // Glass shows its transmission beside its opaque part (alpha 0 alone reads as invisible).
      std::string surface = "alpha " + significant_text(o["alpha"].get<double>(), 3);
      if (o.contains("transmission"))
        surface += "  transmission " + significant_text(o["transmission"].get<double>(), 3);
      std::printf("  %-20s %8lld triangles  %s  interior %s\n",
                  o["name"].get<std::string>().c_str(), (long long)o["triangles"].get<int64_t>(),
                  surface.c_str(), o["interior"].get<std::string>().c_str());
    }
    std::printf("volumes   %zu\n", scene.volumes.size());
    for (const VolumeGrid& v : scene.volumes)
      std::printf("  %-20s %d x %d x %d\n", v.name.c_str(), v.dims.x, v.dims.y, v.dims.z);
    std::printf("lights    %zu\n", scene.lights.size());
    for (const auto& l : j["lights"]) {
      std::string source;
      if (l.contains("source"))
        source = " (from " + l["source"]["intensity"].dump() + " " +
                 l["source"]["unit"].get<std::string>() + ")";
      std::printf("  %-11s color %s  intensity %.6g %s%s\n", l["type"].get<std::string>().c_str(),
                  l["color"].dump().c_str(), l["intensity"].get<double>(),
                  l["unit"].get<std::string>().c_str(), source.c_str());
    }
    std::printf("bounds    %s\n", j["bounds"].dump().c_str());
    std::printf("camera    %s\n", j["camera"].dump().c_str());
    for (const auto& w : j["warnings"]) std::printf("warning   %s\n", w.get<std::string>().c_str());
    return 0;
  };
}

}  // namespace dv::cli
