// Light-map faces fitted to the objects that can cast a shadow. A directional light's
// orthographic face is as wide as the bounding sphere of what it must hold, so its texel size,
// and with it the slope term of the receiver bias (light_faces.h, receiver_depth), follows the
// widest object. A floor plane under the model (the staged ground, six model radii wide) would
// set both: its texels were four times the model's and, for a light 25 degrees above it, the
// bias on the floor grew past the gap under a model resting on it, so the model's bottom face
// dropped out of its own contact shadow. Yet such a plane shadows nothing: every other object
// lies on its lit side. fitted_light_map_layout leaves these planes out of the orthographic
// face's lateral fit (its depth range still holds the whole scene, and the plane is still drawn
// where it falls inside the face); points outside the face are lit, as they are for any map,
// which is right there since no caster lies above them. Spot and omni faces are unchanged.
#pragma once

#include <vector>

#include "engine/raster/light_faces.h"

namespace dv {

// Near plane distance of every light-map face: 1e-4 of the scene diagonal.
double light_map_near(double diagonal);

// The orthographic face of directional light l: laterally centred on `centre`, `radius` to
// each side; its depth range from 2 near planes in front of the sphere (depth_centre,
// depth_radius) to 1 near plane behind it.
ShadowFace orthographic_light_face(const LightView& l, const dvec3& centre, double radius,
                                   const dvec3& depth_centre, double depth_radius, double diagonal,
                                   int res);

// The bounds of `objects` (world bounds per object) without the axis-aligned planes (zero
// extent along an axis) that every other object lies on the lit side of for directional light
// l, that is on the side the light comes from; `bounds` when nothing else remains.
Aabb directional_casters(const LightView& l, const Aabb& bounds, const std::vector<Aabb>& objects);

// light_map_faces with a directional light's face laterally fitted to directional_casters
// (light_map_faces' face where no plane is left out).
std::vector<ShadowFace> fitted_light_map_faces(const LightView& l, const Aabb& bounds,
                                               const std::vector<Aabb>& objects, double diagonal,
                                               int res);

// Every light's faces (per_light[i]: light i's) in one array of res x res texels per face.
LightMapLayout layout_light_faces(const std::vector<std::vector<ShadowFace>>& per_light, int res);

// light_map_layout with every face from fitted_light_map_faces.
LightMapLayout fitted_light_map_layout(const std::vector<LightView>& lights, const Aabb& bounds,
                                       const std::vector<Aabb>& objects, double diagonal, int res);

}  // namespace dv
