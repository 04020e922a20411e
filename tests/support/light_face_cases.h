// Light faces the voxel and GL tests build frustum grids from: a spot light at (0, 4, 0)
// looking down (-y) with a 30-degree half-angle, and a slanted directional light, both fitted
// to the box (-2, 0, -2)..(2, 2, 2).
#pragma once

#include "engine/raster/light_faces.h"
#include "engine/scene/scene_view.h"

namespace dv::test {

inline ShadowFace face_of_light(const Light& l, int res) {
  const Aabb scene{dvec3(-2.0, 0.0, -2.0), dvec3(2.0, 2.0, 2.0)};
  return light_map_faces(make_light_view(l), scene, glm::length(scene.extent()), res)[0];
}

inline ShadowFace spot_face(int res) {
  Light l;
  l.type = LightType::spot;
  l.position = dvec3(0.0, 4.0, 0.0);
  l.direction = dvec3(0.0, -1.0, 0.0);
  l.cutoff_deg = 30.0;
  return face_of_light(l, res);
}

inline ShadowFace sun_face(int res) {
  Light l;
  l.type = LightType::directional;
  l.direction = glm::normalize(dvec3(0.3, -1.0, 0.2));
  return face_of_light(l, res);
}

}  // namespace dv::test
