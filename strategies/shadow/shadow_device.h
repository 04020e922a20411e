// Shadow sources as kernels see them. A shadow source answers
//   transmittance_rgb(cursor, receiver, light)   per colour channel (what shading multiplies)
//   transmittance(cursor, receiver, light)       its luminance
//   (engine/scene/surface_transmittance.h)
// for receivers (shadow_receiver.h: a point, with its geometric normal when it lies on a
// surface) of non-decreasing distance along one camera ray; the small per-ray Cursor lets
// coherent methods (the DSM's incremental lookup) keep state. Kernels are templated on the
// concrete source chosen on the host (std::visit over ShadowSourceVariant): no virtual calls
// in device code. A new shadow method adds its source type here and its host class in its own
// file under strategies/shadow/.
#pragma once

#include <cstdint>
#include <variant>

#include "core/hd.h"
#include "engine/oracle/transmittance.h"
#include "engine/raster/shadow_receiver.h"
#include "engine/scene/scene_view.h"
#include "strategies/shadow/planned_shadow_device.h"
#include "strategies/shadow/shadow_map_device.h"
#include "strategies/shadow/transmittance_slicemap_device.h"
#include "strategies/storage/dsm_device.h"

namespace dv {

// No shadows: every light reaches every point (cone and falloff stay in the light's intensity).
struct NoShadowSource {
  struct Cursor {
    uint32_t flags = 0;
  };
  DV_HD double transmittance(Cursor&, const ShadowReceiver&, int) const { return 1.0; }
  DV_HD dvec3 transmittance_rgb(Cursor&, const ShadowReceiver&, int) const { return dvec3(1.0); }
};

// The exact oracle per shaded sample: slow, the ground truth.
struct ReferenceShadowSource {
  SceneView scene;
  struct Cursor {
    uint32_t flags = 0;  // OracleFlag bits seen along this ray
  };
  DV_HD double transmittance(Cursor& cursor, const ShadowReceiver& r, int light) const {
    return exact(cursor, r, light).transmittance;
  }
  DV_HD dvec3 transmittance_rgb(Cursor& cursor, const ShadowReceiver& r, int light) const {
    return exact(cursor, r, light).rgb;
  }
  DV_HD OracleResult exact(Cursor& cursor, const ShadowReceiver& r, int light) const {
    const OracleResult answer = exact_transmittance(scene, scene.lights[light], r.point);
    cursor.flags |= answer.flags;
    return answer;
  }
};

using ShadowSourceVariant =
    std::variant<NoShadowSource, ReferenceShadowSource, ShadowMapSource, DsmSource,
                 TransmittanceSlicemapSource, PlannedShadowSource>;

}  // namespace dv
