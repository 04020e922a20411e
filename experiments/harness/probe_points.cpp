// Probe point generation (probe_points.h).
#include "experiments/harness/probe_points.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "engine/raster/fragment_walk.h"
#include "strategies/voxelizer/triangle_soup.h"

namespace dv {

namespace {

// Uniform in [0, 1) from the top 53 bits: the same on every standard library.
double uniform(std::mt19937_64& rng) {
  return double(rng() >> 11) * 0x1.0p-53;
}

size_t pick(std::mt19937_64& rng, size_t n) {
  return std::min(n - 1, size_t(uniform(rng) * double(n)));
}

struct SurfaceSampler {
  std::vector<TriangleSoup> objects;      // visible objects' triangles, world space
  std::vector<std::vector<double>> cdfs;  // cumulative areas per object
};

SurfaceSampler surface_sampler(const Scene& scene) {
  SurfaceSampler s;
  for (const Object& o : scene.objects) {
    if (o.material.alpha <= 0.0) continue;
    TriangleSoup soup = triangle_soup(scene.meshes[size_t(o.mesh)], o.transform);
    std::vector<double> cdf;
    double total = 0.0;
    for (int64_t t = 0; t < soup.triangle_count(); ++t) {
      const dvec3* c = &soup.corners[size_t(t) * 3];
      total += 0.5 * glm::length(glm::cross(c[1] - c[0], c[2] - c[0]));
      cdf.push_back(total);
    }
    if (total <= 0.0) continue;
    s.objects.push_back(std::move(soup));
    s.cdfs.push_back(std::move(cdf));
  }
  return s;
}

dvec3 surface_point(const SurfaceSampler& s, std::mt19937_64& rng) {
  const size_t o = pick(rng, s.objects.size());
  const std::vector<double>& cdf = s.cdfs[o];
  const double a = uniform(rng) * cdf.back();
  const size_t t =
      std::min(cdf.size() - 1, size_t(std::upper_bound(cdf.begin(), cdf.end(), a) - cdf.begin()));
  const dvec3* c = &s.objects[o].corners[t * 3];
  double u = uniform(rng), v = uniform(rng);
  if (u + v > 1.0) u = 1.0 - u, v = 1.0 - v;
  return c[0] + (c[1] - c[0]) * u + (c[2] - c[0]) * v;
}

std::vector<Aabb> media_boxes(const Scene& scene) {
  std::vector<Aabb> boxes;
  for (const Object& o : scene.objects) {
    if (o.interior.kind == InteriorKind::none) continue;
    Aabb box;
    for (const dvec3& p : scene.meshes[size_t(o.mesh)].positions)
      box.extend(dvec3(o.transform * dvec4(p, 1.0)));
    boxes.push_back(box);
  }
  return boxes;
}

}  // namespace

const char* to_string(ProbeClass c) {
  switch (c) {
    case ProbeClass::surface:
      return "surface";
    case ProbeClass::medium:
      return "medium";
    case ProbeClass::visible:
      return "visible";
  }
  return "unknown";
}

ProbePoints make_probe_points(const Scene& scene, const SceneData& host, int count,
                              double medium_fraction, uint64_t seed) {
  std::mt19937_64 rng(seed);
  ProbePoints out;
  const std::vector<Aabb> boxes = media_boxes(scene);
  const int medium_wanted =
      boxes.empty() ? 0 : int(std::lround(count * std::clamp(medium_fraction, 0.0, 1.0)));
  for (int tries = 0; int(out.points.size()) < medium_wanted && tries < 200 * medium_wanted;
       ++tries) {
    const Aabb& box = boxes[pick(rng, boxes.size())];
    const dvec3 e = box.extent();
    const dvec3 p = box.lo + dvec3(uniform(rng) * e.x, uniform(rng) * e.y, uniform(rng) * e.z);
    if (media_containing(host.view(), p).inside.count == 0) continue;
    out.points.push_back(p);
    out.classes.push_back(ProbeClass::medium);
  }
  const SurfaceSampler surfaces = surface_sampler(scene);
  while (!surfaces.objects.empty() && int(out.points.size()) < count) {
    out.points.push_back(surface_point(surfaces, rng));
    out.classes.push_back(ProbeClass::surface);
  }
  return out;
}

ProbePoints make_visible_probe_points(const VisibleSurface& view, int count, uint64_t seed) {
  std::vector<size_t> seen;
  for (size_t i = 0; i < view.hit.size(); ++i)
    if (view.hit[i]) seen.push_back(i);
  // A partial Fisher-Yates shuffle: the first `wanted` entries are a uniform draw without
  // replacement.
  std::mt19937_64 rng(seed);
  const size_t wanted = std::min(seen.size(), size_t(std::max(count, 0)));
  ProbePoints out;
  for (size_t k = 0; k < wanted; ++k) {
    std::swap(seen[k], seen[k + pick(rng, seen.size() - k)]);
    out.points.push_back(view.points[seen[k]]);
    out.classes.push_back(ProbeClass::visible);
  }
  return out;
}

}  // namespace dv
