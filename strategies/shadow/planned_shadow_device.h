// Kernel side of the `auto` shadow method (the effect planner, effect_planner.h): each light
// answers through the method the planner chose for it, so one frame mixes methods across lights
// without virtual calls. Per light a PlannedLight names its kind and its source in the array of
// that kind; every per-light source was built for that light alone and answers it as light 0.
// Unshadowed lights (no caster in their cone or range) return 1 inside a spot cone and 0 outside,
// as every map-based method does. DSM lights keep their coherent-search slots in this cursor.
#pragma once

#include <cstdint>

#include "core/hd.h"
#include "cuda/buffer.h"
#include "strategies/shadow/shadow_map_device.h"
#include "strategies/storage/dsm_device.h"

namespace dv {

enum class PlannedKind : uint8_t { unshadowed, depth_map, deep_map };

struct PlannedLight {
  PlannedKind kind;
  int32_t index;  // into PlannedShadowSource::depth_maps or ::deep_maps
};

struct PlannedShadowSource {
  View<const LightView> lights;
  View<const PlannedLight> plan;
  View<const ShadowMapSource> depth_maps;
  View<const DsmSource> deep_maps;

  struct Cursor {
    uint32_t flags = 0;
    DsmSource::Cursor deep;  // per light (the first kDsmCursorLights): coherent-search slots
  };

  DV_HD double transmittance(Cursor& cursor, const ShadowReceiver& r, int light) const {
    return luminance(transmittance_rgb(cursor, r, light));
  }

  DV_HD dvec3 transmittance_rgb(Cursor& cursor, const ShadowReceiver& r, int light) const {
    const PlannedLight& p = plan[light];
    if (p.kind == PlannedKind::depth_map) {
      ShadowMapSource::Cursor unused;
      return depth_maps[p.index].transmittance_rgb(unused, r, 0);
    }
    if (p.kind == PlannedKind::deep_map) {
      int scratch[4] = {-1, -1, -1, -1};
      return deep_maps[p.index].hinted_transmittance(
          r, 0, light < kDsmCursorLights ? cursor.deep.hint + 4 * light : scratch);
    }
    return dvec3(outside_light_cone(lights[light], r.point) ? 0.0 : 1.0);
  }
};

}  // namespace dv
