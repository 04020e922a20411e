// Clustered deep shadow maps (Knecht 2011 §3.4, Bornik et al. 2012 §4), host side: per light the
// scene's objects (meshes with their media and volumes, by world bounding box) are grouped into at
// most m clusters by Algorithm 4.2, and each cluster gets its own focused faces, which hold only
// its objects. Lookups multiply the visibility of every face whose frustum holds the point
// (eq. 3.12; strategies/storage/dsm_device.h).
//
// Distance (§3.4.1): each object's box is projected corner by corner into the light's
// unfocused face (NDC, clipped to the face), or with lispsm into its light-space perspective
// for the camera (engine/dsm/lispsm.h; objects that miss the body B get no map); the
// distance of two objects is the larger of the distances between the projected min points and
// between the projected max points. Omni lights take the maximum over the six cube faces; a face
// that sees only one of the two counts as kApartDistance. Objects that no face sees (outside a spot
// cone) get no map.
//
// Focusing (§3.4.2): a cluster's faces are the light's faces refitted to the cluster's bounds
// (far plane; directional: the orthographic box) and cropped to the window its objects project
// to (an off-axis sub-window of the face, so spot maps stay inside the cone), at equal
// resolution. Omni lights: one cropped cube face per face the cluster touches, so a light whose
// clusters each lie in one direction needs fewer than six maps.
//
// Memory: with m clusters and res R every map has cluster_resolution(R, m) texels per side, the
// largest r with m r^2 <= R^2 (1024 and 4 -> 512), so m clusters cost at most one map of R^2.
#pragma once

#include <string>
#include <vector>

#include "core/math.h"
#include "engine/raster/light_faces.h"
#include "engine/scene/scene_view.h"

namespace dv {

inline constexpr double kApartDistance = 8.0;  // NDC: beyond any distance within one face

struct ClusterSettings {
  int max_clusters = 1;     // m; 1: one unclustered map per light face
  double d0 = 0.5;          // distance threshold in NDC units of the light's face (width 2)
  bool lispsm = false;      // distances in the light-space perspective of the camera (lispsm.h)
  double hysteresis = 0.5;  // keep a clustering while no distance moved more than this * d0
};

// Projected rectangle in a face's NDC, clipped to [-1, 1]^2.
struct NdcRect {
  dvec2 lo{1e300, 1e300};
  dvec2 hi{-1e300, -1e300};
  bool empty() const { return lo.x > hi.x || lo.y > hi.y; }
  void extend(const NdcRect& r) {
    lo = glm::min(lo, r.lo);
    hi = glm::max(hi, r.hi);
  }
};

// Where `box` falls on face f: the NDC bounds of its corners, clipped to the face; empty when it
// lies outside the frustum's sides or behind a perspective face; the whole face when it
// straddles the plane of the light.
NdcRect projected_rect(const ShadowFace& f, const Aabb& box);

// Knecht §3.4.1: max(|a.lo - b.lo|, |a.hi - b.hi|).
double rect_distance(const NdcRect& a, const NdcRect& b);

// Pairwise object distances for one light (symmetric, n x n) and which objects it sees.
struct ObjectDistances {
  int n = 0;
  std::vector<double> d;
  std::vector<bool> seen;
  double at(int i, int j) const { return d[size_t(i) * n + j]; }
};
// With `camera` the boxes are compared in each face's light-space perspective for it
// (lispsm.h), and objects outside its body B are not seen.
ObjectDistances light_object_distances(const LightView& light, const std::vector<Aabb>& objects,
                                       const Aabb& scene_bounds, double diagonal,
                                       const Camera* camera = nullptr);

// Algorithm 4.2 over the seen objects: pairs in ascending distance (§3.4.1 step 1), each object
// into the first cluster whose members are all within d0, else a new cluster while fewer than
// max_clusters exist, else the nearest cluster (smallest maximum distance to its members).
// Clusters in order of creation, members ascending.
std::vector<std::vector<int>> cluster_objects(const ObjectDistances& distances, int max_clusters,
                                              double d0);

// The largest r with m r^2 <= res^2.
int cluster_resolution(int res, int max_clusters);

// `projection` restricted to the NDC window `rect` (which then fills the image).
RasterProjection crop_projection(const RasterProjection& projection, const NdcRect& rect);

// A cluster's focused faces (offsets left 0).
std::vector<ShadowFace> cluster_faces(const LightView& light, const std::vector<Aabb>& objects,
                                      const std::vector<int>& cluster, int res);

// Every light's clusters and their faces, with offsets, the per-face object masks
// (engine/dsm/object_mask.h) and a signature that changes when a cluster or a frustum does.
struct ClusteredLayout {
  LightMapLayout layout;
  int resolution = 0;
  int mask_words = 0;
  std::vector<uint32_t> object_masks;                   // per face mask_words words
  std::vector<std::vector<std::vector<int>>> clusters;  // per light, per cluster: object ids
  std::vector<int> face_cluster;                        // per face: its cluster within its light
  std::vector<ObjectDistances> distances;               // per light: what the clusters came from
  std::string signature;
};

// Every light's object distances (light_object_distances; with settings.lispsm, for `camera`).
std::vector<ObjectDistances> light_distances(const std::vector<LightView>& lights,
                                             const std::vector<Aabb>& objects,
                                             const Aabb& scene_bounds, double diagonal,
                                             const ClusterSettings& settings, const Camera* camera);

// Hysteresis: `layout` still serves distances `now` when every object seen now was seen then
// (so it has a map) and no distance between two of them moved by more than hysteresis * d0
// since the clustering was made.
bool clustering_holds(const ClusteredLayout& layout, const std::vector<ObjectDistances>& now,
                      const ClusterSettings& settings);
// `distances`: light_distances() for the same lights and objects.
ClusteredLayout clustered_light_map_layout(const std::vector<LightView>& lights,
                                           const std::vector<Aabb>& objects,
                                           std::vector<ObjectDistances> distances,
                                           const ClusterSettings& settings, int res);

}  // namespace dv
