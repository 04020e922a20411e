// The faces of light-space maps (shadow maps, deep shadow maps): per light one face (spot:
// perspective over the cone; directional: orthographic fitted to the casters) or six 90-degree
// faces (omni), each a square map of res x res texels, and the kernel-side helpers every map
// lookup shares: which face a point falls on, where it projects, its depth, the receiver bias.
// Depth everywhere (generation, storage, lookups) is the distance from the light for
// perspective faces and the distance along the axis from the near plane for orthographic ones,
// which is the parameter t of the face's pixel rays (engine/raster/raster_projection.h).
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "core/hd.h"
#include "core/math.h"
#include "engine/raster/raster_projection.h"
#include "engine/raster/shadow_receiver.h"
#include "engine/scene/scene_view.h"

namespace dv {

struct ShadowFace {
  RasterProjection projection;  // world -> clip of this face, res x res texels
  dvec3 eye;                    // perspective: the light; orthographic: centre of the near plane
  dvec3 axis;                   // unit viewing direction
  bool orthographic;
  double texel_size;  // world size of a texel: per unit depth (perspective) or absolute
  int64_t offset;     // first texel of this face in the map's texel arrays
};

struct ShadowLight {
  int32_t first_face;
  int32_t face_count;  // 1 (spot, directional) or 6 (omni); clustered: any number
  // Clustered deep shadow maps (engine/dsm/light_clusters.h): each face holds some of the
  // objects, and every face whose frustum holds a point contributes (Knecht 2011 eq. 3.12).
  bool clustered = false;
};

// The depth a map stores and compares (see the file comment).
DV_HD inline double shadow_depth(const ShadowFace& f, const dvec3& x) {
  return f.orthographic ? glm::dot(x - f.eye, f.axis) : glm::length(x - f.eye);
}

// Spot lights: p outside the cone gets no light at all (as the oracle answers).
DV_HD inline bool outside_light_cone(const LightView& l, const dvec3& p) {
  if (l.type != LightType::spot) return false;
  const dvec3 d = p - l.position;
  const double len = glm::length(d);
  return len > 0.0 && outside_spot_cone(l, d / len);
}

// Omni lights: the cube face whose axis is the major axis of p - light.
DV_HD inline int face_of(const ShadowLight& sl, const LightView& l, const dvec3& p) {
  if (sl.face_count == 1) return sl.first_face;
  const dvec3 d = p - l.position;
  const dvec3 a = glm::abs(d);
  const int axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
  return sl.first_face + 2 * axis + (d[axis] < 0.0 ? 1 : 0);
}

// Where a point falls on a face: texel-centre coordinates (texel (x, y) is centred on (x, y))
// and its depth.
struct FacePoint {
  double u, v;
  double depth;
};

// False when p is behind a perspective face's centre of projection.
DV_HD inline bool project_to_face(const ShadowFace& f, int resolution, const dvec3& p,
                                  FacePoint& out) {
  const dvec4 clip = world_to_clip_point(f.projection, p);
  if (clip.w <= 0.0 && !f.orthographic) return false;
  out.u = (clip.x / clip.w * 0.5 + 0.5) * resolution - 0.5;
  out.v = (0.5 - clip.y / clip.w * 0.5) * resolution - 0.5;
  out.depth = shadow_depth(f, p);
  return true;
}

// Largest receiver tangent the slope bias follows: 86.4 degrees between the normal and the
// light, where the diffuse term n.l has fallen to 0.062.
inline constexpr double kMaxBiasTangent = 16.0;

// The depth a lookup compares against the map for receiver r at `depth` on face f. A surface
// point is moved towards the light by the constant `bias` plus `slope` x `texels` (the
// filter's reach) texel sizes at its depth times tan(theta), theta the angle between its
// normal and the direction to the light (capped at kMaxBiasTangent): the depth its own plane
// changes by over that reach (receiver-plane bias; Brabec 2003 ch. 5), so grazing receivers
// escape self-shadowing and surfaces facing the light keep only the constant. A point not on a
// surface (media, volume samples, free probe points) is not biased.
DV_HD inline double receiver_depth(const ShadowFace& f, const ShadowReceiver& r, double depth,
                                   double bias, double slope, double texels) {
  if (!r.on_surface()) return depth;
  dvec3 to_light = -f.axis;
  if (!f.orthographic) {
    const dvec3 d = f.eye - r.point;
    const double len = glm::length(d);
    if (len > 0.0) to_light = d / len;
  }
  const double c = glm::dot(r.normal, to_light), cos_theta = c < 0.0 ? -c : c;
  const double sin_theta = sqrt(max_value(0.0, 1.0 - cos_theta * cos_theta));
  const double tangent =
      sin_theta >= kMaxBiasTangent * cos_theta ? kMaxBiasTangent : sin_theta / cos_theta;
  const double texel = f.orthographic ? f.texel_size : depth * f.texel_size;
  return depth - bias - slope * texel * texels * tangent;
}

// The faces of one light's map at res x res texels, fitted to `bounds` (the casters): near
// plane 1e-4 of the diagonal, far plane at the farthest corner. Offsets are left 0.
std::vector<ShadowFace> light_map_faces(const LightView& light, const Aabb& bounds, double diagonal,
                                        int res);

// Every light's faces with offsets into one array of res x res texels per face.
struct LightMapLayout {
  std::vector<ShadowFace> faces;
  std::vector<ShadowLight> lights;
  int64_t texels_per_face = 0;
  int64_t texel_count() const { return texels_per_face * int64_t(faces.size()); }
};
LightMapLayout light_map_layout(const std::vector<LightView>& lights, const Aabb& bounds,
                                double diagonal, int res);

// The lights a set of maps is made for: all of `lights` (light < 0), or only lights[light] (the
// planner's per-light maps, whose lookups then answer it as light 0).
std::vector<LightView> mapped_lights(const std::vector<LightView>& lights, int light);

}  // namespace dv
