// The effect planner: before a frame, what each light needs, decided on the host
// from the scene's object bounds and materials, so the `auto` shadow method
// (auto_shadows.cpp) runs only that. Per light:
//   - the casters it reaches: objects that cast (alpha > 0 or glass, a constant medium or a
//     volume) whose bounding box meets its cone (spot) and range window (spot, omni; directional:
//     everything);
//   - the method: none when it reaches no caster (no map, no lookups), `shadowmap` (one depth
//     layer) when every caster is opaque (alpha >= 1, no interior, no BLEND texture; a MASK
//     texture's cut-outs are cut per texel by the depth map), `dsm` otherwise, with volume
//     sampling in generation only when a volume is among its casters;
//   - omni lights: the cube faces whose pyramid a caster's box may enter (a conservative test);
//   - a content key of everything its map depends on (light geometry, the scene bounds the faces
//     are fitted to, each reached caster's content hash), so maps are rebuilt only when it changes.
// A caster outside a light's cone or range cannot shadow a point inside it (the segment from the
// light to such a point stays inside the cone and the range ball), and points outside receive
// none of its light, so skipping them changes no pixel.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/scene/scene_view.h"

namespace dv {

enum class PlannedMethod : uint8_t { none, shadowmap, dsm };
const char* to_string(PlannedMethod m);

// What one light reaches.
struct LightReach {
  std::vector<int> casters;  // object indices, ascending
  int opaque = 0, translucent = 0, media = 0, volumes = 0;
  std::vector<uint8_t> faces;  // per face of its standard layout: 1 where a caster may project
};

struct LightPlan {
  PlannedMethod method = PlannedMethod::none;
  std::string reason;  // why, in plain words
  LightReach reach;
  bool volume_sampling = false;      // dsm generation samples volumes
  std::vector<std::string> skipped;  // passes not run for this light, plain words
  uint64_t light_key = 0;            // the light's geometry (what its faces depend on)
  uint64_t casters_key = 0;          // the reached casters' indices and content hashes
  uint64_t bounds_key = 0;           // the scene bounds the faces are fitted to
};

// Whether a light reaches an axis-aligned box (cone and range; conservative: may say yes for a
// box just outside, never no for a box it reaches).
bool light_reaches(const LightView& light, const Aabb& box);
// Omni lights: whether a box may enter the pyramid of cube face `face` (+X, -X, +Y, -Y, +Z, -Z).
bool omni_face_reaches(const LightView& light, int face, const Aabb& box);

LightReach light_reach(const SceneData& scene, int light);
LightPlan plan_light(const SceneData& scene, int light);

// Objects with a volume interior: the camera's walk samples volumes only inside them (the plan
// reports it; with none, no camera segment is sampled).
int volume_objects(const SceneData& scene);

// The plan of one frame (the `auto` method's stats "frames" entry) in plain words, one line per
// light: what `--explain` prints.
std::string explain_plan(const nlohmann::json& frame);

}  // namespace dv
