// The effect planner's per-light decisions (see effect_planner.h).
#include "strategies/shadow/effect_planner.h"

#include <algorithm>
#include <cmath>

#include "core/content_hash.h"
#include "engine/scene/surface_transmittance.h"

namespace dv {

namespace {

constexpr double kPi = 3.14159265358979323846;

// The smallest |x| over [lo, hi].
double min_abs(double lo, double hi) {
  return lo <= 0.0 && hi >= 0.0 ? 0.0 : std::min(std::abs(lo), std::abs(hi));
}

bool casts(const ObjectView& o) {
  return material_coverage(o) > 0.0 || o.interior != InteriorKind::none;
}

std::string count_of(int n, const char* what) {
  return std::to_string(n) + " " + what + (n == 1 ? "" : "s");
}

// Spot lights: whether the box lies wholly outside one side of the square pyramid around the
// cone (half-angle = the cutoff; the half-space in front of the light for cutoffs up to 90
// degrees).
bool outside_cone_pyramid(const LightView& l, const Aabb& box) {
  const double cutoff = std::acos(std::clamp(l.cos_cutoff, -1.0, 1.0));
  if (cutoff >= 0.5 * kPi) return false;
  const double slope = std::tan(cutoff);
  const dvec3 side = std::abs(l.direction.y) < 0.9 ? dvec3(0, 1, 0) : dvec3(1, 0, 0);
  const dvec3 right = glm::normalize(glm::cross(l.direction, side));
  const dvec3 up = glm::cross(right, l.direction);
  bool outside[5] = {true, true, true, true, true};  // +x, -x, +y, -y, behind
  for (int corner = 0; corner < 8; ++corner) {
    const dvec3 c(corner & 1 ? box.hi.x : box.lo.x, corner & 2 ? box.hi.y : box.lo.y,
                  corner & 4 ? box.hi.z : box.lo.z);
    const dvec3 d = c - l.position;
    const double x = glm::dot(d, right), y = glm::dot(d, up), z = glm::dot(d, l.direction);
    outside[0] = outside[0] && x > slope * z;
    outside[1] = outside[1] && -x > slope * z;
    outside[2] = outside[2] && y > slope * z;
    outside[3] = outside[3] && -y > slope * z;
    outside[4] = outside[4] && z < 0.0;
  }
  return outside[0] || outside[1] || outside[2] || outside[3] || outside[4];
}

// Spot lights: whether the cone meets the box's bounding sphere (the angle from the axis to the
// sphere's centre, less the sphere's angular radius, within the cutoff).
bool cone_meets_sphere_of(const LightView& l, const Aabb& box) {
  const dvec3 to_centre = box.center() - l.position;
  const double d = glm::length(to_centre), radius = 0.5 * glm::length(box.extent());
  if (d <= radius) return true;
  const double to_axis = std::acos(std::clamp(glm::dot(to_centre / d, l.direction), -1.0, 1.0));
  const double cutoff = std::acos(std::clamp(l.cos_cutoff, -1.0, 1.0));
  return to_axis - std::asin(radius / d) <= cutoff + 1e-9;
}

}  // namespace

const char* to_string(PlannedMethod m) {
  return m == PlannedMethod::none ? "none" : m == PlannedMethod::shadowmap ? "shadowmap" : "dsm";
}

bool light_reaches(const LightView& l, const Aabb& box) {
  if (box.empty()) return false;
  if (l.type == LightType::directional) return true;
  if (l.range > 0.0) {
    const dvec3 nearest = glm::clamp(l.position, box.lo, box.hi);
    if (glm::length(nearest - l.position) > l.range) return false;
  }
  if (l.type != LightType::spot) return true;
  return !outside_cone_pyramid(l, box) && cone_meets_sphere_of(l, box);
}

bool omni_face_reaches(const LightView& l, int face, const Aabb& box) {
  const int a = face / 2, b = (a + 1) % 3, c = (a + 2) % 3;
  const dvec3 lo = box.lo - l.position, hi = box.hi - l.position;
  // Face (a, sign) holds the points with sign * d_a >= |d_b| and >= |d_c|: the box may meet it
  // only if its largest sign * d_a reaches the smallest |d_b| and the smallest |d_c|.
  const double reach = face % 2 == 0 ? hi[a] : -lo[a];
  return reach >= min_abs(lo[b], hi[b]) && reach >= min_abs(lo[c], hi[c]);
}

LightReach light_reach(const SceneData& scene, int light) {
  const LightView& l = scene.host_lights()[size_t(light)];
  const std::vector<ObjectView>& objects = scene.host_objects();
  const std::vector<Aabb>& boxes = scene.host_object_bounds();
  LightReach r;
  r.faces.assign(l.type == LightType::omni ? 6 : 1, 0);
  for (size_t i = 0; i < objects.size(); ++i) {
    const ObjectView& o = objects[i];
    if (!casts(o) || !light_reaches(l, boxes[i])) continue;
    r.casters.push_back(int(i));
    if (o.interior == InteriorKind::volume)
      ++r.volumes;
    else if (o.interior == InteriorKind::constant)
      ++r.media;
    else if (o.alpha >= 1.0 && !(o.texture >= 0 && o.alpha_mode == AlphaMode::blend))
      ++r.opaque;  // a MASK texture leaves it opaque where covered: a depth map cuts it per texel
    else
      ++r.translucent;
    for (size_t f = 0; f < r.faces.size(); ++f)
      if (l.type != LightType::omni || omni_face_reaches(l, int(f), boxes[i])) r.faces[f] = 1;
  }
  return r;
}

LightPlan plan_light(const SceneData& scene, int light) {
  const LightView& l = scene.host_lights()[size_t(light)];
  LightPlan p;
  p.reach = light_reach(scene, light);
  const LightReach& r = p.reach;
  const int casters = int(r.casters.size());
  if (casters == 0) {
    p.method = PlannedMethod::none;
    p.reason = l.type == LightType::directional ? "the scene has no shadow caster"
               : l.type == LightType::spot      ? "its cone and range reach no shadow caster"
                                                : "its range reaches no shadow caster";
    p.skipped = {"map generation", "shadow lookups"};
  } else if (r.opaque == casters) {
    p.method = PlannedMethod::shadowmap;
    p.reason = "every caster it reaches is opaque (" + count_of(casters, "object") +
               "): one depth layer holds its shadow";
    p.skipped = {"deep-map generation and compression", "volume sampling in generation"};
    const int empty = int(std::count(r.faces.begin(), r.faces.end(), uint8_t(0)));
    if (empty > 0)
      p.skipped.push_back(std::to_string(empty) + " of 6 cube faces (no caster in them)");
  } else {
    p.method = PlannedMethod::dsm;
    p.volume_sampling = r.volumes > 0;
    if (p.volume_sampling) {
      p.reason =
          "it reaches " + count_of(r.volumes, "volume") + ": a deep map with volume sampling";
    } else {
      std::string seen;
      if (r.translucent) seen = count_of(r.translucent, "translucent surface");
      if (r.media) seen += (seen.empty() ? "" : " and ") + count_of(r.media, "constant medium");
      p.reason = "it reaches " + seen + " but no volume: a deep map without volume sampling";
      p.skipped = {"volume sampling in generation"};
    }
  }
  ContentHash light_hash;
  light_hash.add(l.type).add(l.position).add(l.direction).add(l.cos_cutoff).add(l.range);
  p.light_key = light_hash.value();
  ContentHash casters_hash;
  for (int i : r.casters) casters_hash.add(i).add(scene.host_object_hashes()[size_t(i)]);
  p.casters_key = casters_hash.value();
  const SceneView& s = scene.view();
  ContentHash bounds_hash;
  bounds_hash.add(s.bounds.lo).add(s.bounds.hi).add(s.diagonal);
  p.bounds_key = bounds_hash.value();
  return p;
}

int volume_objects(const SceneData& scene) {
  int n = 0;
  for (const ObjectView& o : scene.host_objects()) n += o.interior == InteriorKind::volume;
  return n;
}

std::string explain_plan(const nlohmann::json& frame) {
  const int volumes = frame.value("volume_objects", 0);
  std::string out = volumes == 0 ? "camera rays: no volume in the scene, no volume sampling\n"
                                 : "camera rays: volume sampling only inside the " +
                                       count_of(volumes, "volume object") + "\n";
  for (const nlohmann::json& l : frame.at("lights")) {
    out += "light " + std::to_string(l.at("light").get<int>()) + " (" +
           l.at("type").get<std::string>() + "): " + l.at("method").get<std::string>() + ", " +
           l.at("reason").get<std::string>() + "; ";
    const std::string map = l.at("map").get<std::string>();
    out += map == "none" ? "no map" : "map " + map;
    if (l.contains("map_reason")) out += " (" + l.at("map_reason").get<std::string>() + ")";
    if (!l.at("skipped").empty()) {
      out += "; skipped:";
      bool first = true;
      for (const nlohmann::json& s : l.at("skipped")) {
        out += (first ? " " : ", ") + s.get<std::string>();
        first = false;
      }
    }
    out += "\n";
  }
  return out;
}

}  // namespace dv
