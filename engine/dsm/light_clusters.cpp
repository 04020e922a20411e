// Clustering of objects per light and the clusters' focused faces (see light_clusters.h).
#include "engine/dsm/light_clusters.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "engine/dsm/lispsm.h"

namespace dv {

NdcRect projected_rect(const ShadowFace& f, const Aabb& box) {
  NdcRect r;
  if (box.empty()) return r;
  bool behind = false, in_front = false;
  for (int c = 0; c < 8; ++c) {
    const dvec3 corner((c & 1) ? box.hi.x : box.lo.x, (c & 2) ? box.hi.y : box.lo.y,
                       (c & 4) ? box.hi.z : box.lo.z);
    const dvec4 clip = world_to_clip_point(f.projection, corner);
    if (!f.orthographic && clip.w <= 0.0) {
      behind = true;
      continue;
    }
    in_front = true;
    const dvec2 ndc(clip.x / clip.w, clip.y / clip.w);
    r.lo = glm::min(r.lo, ndc);
    r.hi = glm::max(r.hi, ndc);
  }
  if (!in_front) return NdcRect{};
  if (behind) r = NdcRect{dvec2(-1.0), dvec2(1.0)};
  r.lo = glm::max(r.lo, dvec2(-1.0));
  r.hi = glm::min(r.hi, dvec2(1.0));
  return r.empty() ? NdcRect{} : r;
}

double rect_distance(const NdcRect& a, const NdcRect& b) {
  return std::max(glm::length(a.lo - b.lo), glm::length(a.hi - b.hi));
}

ObjectDistances light_object_distances(const LightView& light, const std::vector<Aabb>& objects,
                                       const Aabb& scene_bounds, double diagonal,
                                       const Camera* camera) {
  ObjectDistances out;
  out.n = int(objects.size());
  out.d.assign(size_t(out.n) * out.n, 0.0);
  out.seen.assign(size_t(out.n), false);
  for (const ShadowFace& f : light_map_faces(light, scene_bounds, diagonal, 1)) {
    LispsmSpace space;
    if (camera) space = lispsm_space(f, light, *camera, scene_bounds, diagonal);
    std::vector<NdcRect> rects;
    for (int i = 0; i < out.n; ++i) {
      NdcRect r;
      if (!camera) r = projected_rect(f, objects[size_t(i)]);
      if (camera && !space.box_rect(objects[size_t(i)], r.lo, r.hi)) r = NdcRect{};
      rects.push_back(r);
      if (!rects.back().empty()) out.seen[size_t(i)] = true;
    }
    for (int i = 0; i < out.n; ++i)
      for (int j = 0; j < out.n; ++j) {
        const bool ei = rects[size_t(i)].empty(), ej = rects[size_t(j)].empty();
        if (i == j || (ei && ej)) continue;
        const double d =
            ei || ej ? kApartDistance : rect_distance(rects[size_t(i)], rects[size_t(j)]);
        double& slot = out.d[size_t(i) * out.n + j];
        slot = std::max(slot, d);
      }
  }
  return out;
}

namespace {

struct ObjectPair {
  double d;
  int a, b;
};

class Clustering {
 public:
  Clustering(const ObjectDistances& distances, int max_clusters, double d0)
      : d_(distances), m_(max_clusters), d0_(d0), cluster_of_(size_t(distances.n), -1) {}

  bool placed(int o) const { return cluster_of_[size_t(o)] >= 0; }
  bool full() const { return int(clusters_.size()) >= m_; }

  // Into the first cluster whose members are all within d0 of o.
  void place_if_close(int o) {
    for (size_t k = 0; k < clusters_.size() && !placed(o); ++k)
      if (max_distance(o, clusters_[k]) <= d0_) add(o, int(k));
  }
  void open(int o) {
    clusters_.emplace_back();
    add(o, int(clusters_.size()) - 1);
  }
  void add_to_open(int o) { add(o, int(clusters_.size()) - 1); }
  // Into the cluster with the smallest maximum distance to its members.
  void place_nearest(int o) {
    int best = 0;
    for (size_t k = 1; k < clusters_.size(); ++k)
      if (max_distance(o, clusters_[k]) < max_distance(o, clusters_[size_t(best)])) best = int(k);
    add(o, best);
  }
  std::vector<std::vector<int>> take() {
    for (std::vector<int>& c : clusters_) std::sort(c.begin(), c.end());
    return std::move(clusters_);
  }

 private:
  double max_distance(int o, const std::vector<int>& cluster) const {
    double d = 0.0;
    for (int j : cluster) d = std::max(d, d_.at(o, j));
    return d;
  }
  void add(int o, int k) {
    clusters_[size_t(k)].push_back(o);
    cluster_of_[size_t(o)] = k;
  }

  const ObjectDistances& d_;
  int m_;
  double d0_;
  std::vector<int> cluster_of_;
  std::vector<std::vector<int>> clusters_;
};

}  // namespace

std::vector<std::vector<int>> cluster_objects(const ObjectDistances& distances, int max_clusters,
                                              double d0) {
  std::vector<int> seen;
  for (int i = 0; i < distances.n; ++i)
    if (distances.seen[size_t(i)]) seen.push_back(i);
  Clustering c(distances, std::max(max_clusters, 1), d0);
  if (seen.size() == 1) c.open(seen[0]);
  std::vector<ObjectPair> pairs;
  for (size_t i = 0; i < seen.size(); ++i)
    for (size_t j = i + 1; j < seen.size(); ++j)
      pairs.push_back({distances.at(seen[i], seen[j]), seen[i], seen[j]});
  std::sort(pairs.begin(), pairs.end(), [](const ObjectPair& x, const ObjectPair& y) {
    return x.d != y.d ? x.d < y.d : (x.a != y.a ? x.a < y.a : x.b < y.b);
  });
  for (const ObjectPair& p : pairs) {
    if (!c.placed(p.a)) c.place_if_close(p.a);
    if (!c.placed(p.b)) c.place_if_close(p.b);
    if (c.placed(p.a) && c.placed(p.b)) continue;
    if (c.full()) {
      if (!c.placed(p.a)) c.place_nearest(p.a);
      if (!c.placed(p.b)) c.place_nearest(p.b);
    } else if (p.d <= d0 && !c.placed(p.a) && !c.placed(p.b)) {
      c.open(p.a);
      c.add_to_open(p.b);
    } else {
      if (!c.placed(p.a)) c.open(p.a);
      if (!c.placed(p.b)) c.full() ? c.place_nearest(p.b) : c.open(p.b);
    }
  }
  return c.take();
}

int cluster_resolution(int res, int max_clusters) {
  const int64_t area = int64_t(res) * res;
  int64_t r = res;
  while (r > 1 && r * r * max_clusters > area) --r;
  return int(r);
}

RasterProjection crop_projection(const RasterProjection& projection, const NdcRect& rect) {
  const dvec2 size = rect.hi - rect.lo;
  dmat4 s(1.0);
  s[0][0] = 2.0 / size.x;
  s[3][0] = -(rect.lo.x + rect.hi.x) / size.x;
  s[1][1] = 2.0 / size.y;
  s[3][1] = -(rect.lo.y + rect.hi.y) / size.y;
  RasterProjection p = projection;
  p.world_to_clip = s * projection.world_to_clip;
  p.clip_to_world = glm::inverse(p.world_to_clip);
  return p;
}

std::vector<ShadowFace> cluster_faces(const LightView& light, const std::vector<Aabb>& objects,
                                      const std::vector<int>& cluster, int res) {
  Aabb box;
  for (int o : cluster) box.extend(objects[size_t(o)]);
  const double diagonal = glm::length(box.extent()) + 1e-9;
  std::vector<ShadowFace> faces;
  for (ShadowFace f : light_map_faces(light, box, diagonal, res)) {
    NdcRect window;
    for (int o : cluster) window.extend(projected_rect(f, objects[size_t(o)]));
    if (window.empty()) continue;
    // Two texels of margin against rounding at the window's edge, and no degenerate window.
    const dvec2 size = glm::max(window.hi - window.lo, dvec2(1e-6));
    const dvec2 margin = size * (2.0 / std::max(res - 4, 1));
    const dvec2 centre = 0.5 * (window.lo + window.hi);
    window.lo = glm::max(centre - 0.5 * size - margin, dvec2(-1.0));
    window.hi = glm::min(centre + 0.5 * size + margin, dvec2(1.0));
    f.projection = crop_projection(f.projection, window);
    f.texel_size *= 0.5 * std::max(window.hi.x - window.lo.x, window.hi.y - window.lo.y);
    faces.push_back(f);
  }
  return faces;
}

namespace {

void append_signature(std::string& s, const ShadowFace& f) {
  char buffer[32];
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) {
      std::snprintf(buffer, sizeof buffer, "%.9g,", f.projection.world_to_clip[c][r]);
      s += buffer;
    }
}

}  // namespace

std::vector<ObjectDistances> light_distances(const std::vector<LightView>& lights,
                                             const std::vector<Aabb>& objects,
                                             const Aabb& scene_bounds, double diagonal,
                                             const ClusterSettings& settings,
                                             const Camera* camera) {
  std::vector<ObjectDistances> out;
  for (const LightView& l : lights)
    out.push_back(light_object_distances(l, objects, scene_bounds, diagonal,
                                         settings.lispsm ? camera : nullptr));
  return out;
}

bool clustering_holds(const ClusteredLayout& layout, const std::vector<ObjectDistances>& now,
                      const ClusterSettings& settings) {
  if (layout.distances.size() != now.size()) return false;
  const double tolerance = settings.hysteresis * settings.d0;
  for (size_t l = 0; l < now.size(); ++l) {
    const ObjectDistances& a = layout.distances[l];
    const ObjectDistances& b = now[l];
    if (a.n != b.n) return false;
    for (int i = 0; i < b.n; ++i) {
      if (!b.seen[size_t(i)]) continue;
      if (!a.seen[size_t(i)]) return false;
      for (int j = 0; j < b.n; ++j)
        if (b.seen[size_t(j)] && std::abs(b.at(i, j) - a.at(i, j)) > tolerance) return false;
    }
  }
  return true;
}

ClusteredLayout clustered_light_map_layout(const std::vector<LightView>& lights,
                                           const std::vector<Aabb>& objects,
                                           std::vector<ObjectDistances> distances,
                                           const ClusterSettings& settings, int res) {
  ClusteredLayout out;
  out.resolution = cluster_resolution(res, settings.max_clusters);
  out.mask_words = int(objects.size() + 31) / 32;
  out.layout.texels_per_face = int64_t(out.resolution) * out.resolution;
  for (size_t li = 0; li < lights.size(); ++li) {
    const LightView& l = lights[li];
    std::vector<std::vector<int>> clusters =
        cluster_objects(distances[li], settings.max_clusters, settings.d0);
    const int32_t first = int32_t(out.layout.faces.size());
    out.signature += "L";
    for (size_t k = 0; k < clusters.size(); ++k) {
      out.signature += "C";
      for (int o : clusters[k]) out.signature += std::to_string(o) + ",";
      for (const ShadowFace& f : cluster_faces(l, objects, clusters[k], out.resolution)) {
        append_signature(out.signature, f);
        out.layout.faces.push_back(f);
        out.face_cluster.push_back(int(k));
        std::vector<uint32_t> mask(size_t(out.mask_words), 0u);
        for (int o : clusters[k]) mask[size_t(o / 32)] |= 1u << (o % 32);
        out.object_masks.insert(out.object_masks.end(), mask.begin(), mask.end());
      }
    }
    out.layout.lights.push_back(
        {first, int32_t(out.layout.faces.size()) - first, /*clustered=*/true});
    out.clusters.push_back(std::move(clusters));
  }
  for (size_t i = 0; i < out.layout.faces.size(); ++i)
    out.layout.faces[i].offset = int64_t(i) * out.layout.texels_per_face;
  out.distances = std::move(distances);
  return out;
}

}  // namespace dv
