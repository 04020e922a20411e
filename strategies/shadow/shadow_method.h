// Host side of the shadow-method family: a registered, named strategy that prepares whatever
// it needs for a scene (maps, grids) and hands kernels a concrete shadow source.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/registry.h"
#include "cuda/execute.h"
#include "engine/scene/scene_view.h"
#include "strategies/shadow/shadow_device.h"

namespace dv {

class DeepShadowMaps;
class VoxelGrid;

class ShadowMethod {
 public:
  virtual ~ShadowMethod() = default;
  virtual std::string name() const = 0;
  virtual nlohmann::json params() const = 0;
  // What the method did so far (maps built, bytes, build times); empty for stateless methods.
  virtual nlohmann::json stats() const { return nlohmann::json::object(); }
  // `scene` lives in the memory of `backend`; the returned source refers into it (and into
  // whatever the method built), so it stays valid while both live. `view` is the camera the
  // answers are for (methods that focus on what it sees use it), or null for queries anywhere.
  virtual ShadowSourceVariant prepare(const SceneData& scene, Backend backend,
                                      const Camera* view) = 0;
  // The deep shadow maps the last prepare generated or kept, for inspection (heat maps); null
  // for methods without them and before the first prepare.
  virtual const DeepShadowMaps* deep_shadow_maps() const { return nullptr; }
  // The voxel grids the last prepare built (one per light face, in face order), for inspection
  // (the viewer's grid overlay); null for methods without them and before the first prepare.
  virtual const std::vector<VoxelGrid>* voxel_grids() const { return nullptr; }
  // The last prepare's plan (the `auto` method: per light the method, maps and passes skipped,
  // effect_planner.h); null for methods that do not plan.
  virtual nlohmann::json plan() const { return nullptr; }
};

Registry<ShadowMethod>& shadow_registry();

}  // namespace dv
