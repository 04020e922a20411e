// Probe point generation (probe_points.h): mesh surfaces, isosurfaces of volumes, media.
#include "experiments/harness/probe_points.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "engine/raster/fragment_walk.h"
#include "engine/scene/volume_sampling.h"
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

Aabb world_box(const Scene& scene, const Object& o) {
  Aabb box;
  for (const dvec3& p : scene.meshes[size_t(o.mesh)].positions)
    box.extend(dvec3(o.transform * dvec4(p, 1.0)));
  return box;
}

std::vector<Aabb> media_boxes(const Scene& scene) {
  std::vector<Aabb> boxes;
  for (const Object& o : scene.objects)
    if (o.interior.kind != InteriorKind::none) boxes.push_back(world_box(scene, o));
  return boxes;
}

// Volume objects whose isosurface at `isovalue` holds surface probes: their indices and world
// boxes.
struct IsosurfaceSampler {
  std::vector<int> objects;
  std::vector<Aabb> boxes;
  double isovalue = -1.0;
};

IsosurfaceSampler isosurface_sampler(const Scene& scene, double isovalue) {
  IsosurfaceSampler s;
  s.isovalue = isovalue;
  if (isovalue < 0.0) return s;
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const Object& o = scene.objects[i];
    if (o.interior.kind != InteriorKind::volume) continue;
    s.objects.push_back(int(i));
    s.boxes.push_back(world_box(scene, o));
  }
  return s;
}

// A point on the isosurface of one of s's volumes: from a uniform point of its box along a
// uniform direction, the first crossing of the isovalue (trilinear density, 512 steps over the
// box's diagonal, then bisection); tries again from another point when the line crosses none.
// False after 200 tries.
bool isosurface_point(const IsosurfaceSampler& s, const SceneData& host, std::mt19937_64& rng,
                      dvec3& out) {
  const SceneView& view = host.view();
  const size_t k = pick(rng, s.objects.size());
  const ObjectView& o = view.objects[s.objects[k]];
  const Aabb& box = s.boxes[k];
  const auto level = [&](const dvec3& x) {
    return density_at_grid(view, view.volumes[o.volume], world_to_grid(o, x)) - s.isovalue;
  };
  const double diagonal = glm::length(box.extent());
  for (int tries = 0; tries < 200; ++tries) {
    const dvec3 e = box.extent();
    const dvec3 p = box.lo + dvec3(uniform(rng) * e.x, uniform(rng) * e.y, uniform(rng) * e.z);
    dvec3 d;
    do d = dvec3(uniform(rng), uniform(rng), uniform(rng)) * 2.0 - 1.0;
    while (glm::dot(d, d) > 1.0 || glm::dot(d, d) < 1e-6);
    d = glm::normalize(d) * (diagonal / 512.0);
    double f0 = level(p);
    for (int i = 1; i <= 512; ++i) {
      const dvec3 a = p + d * double(i - 1), b = p + d * double(i);
      if (glm::any(glm::lessThan(b, box.lo)) || glm::any(glm::greaterThan(b, box.hi))) break;
      const double f1 = level(b);
      if ((f0 < 0.0) != (f1 < 0.0)) {
        double lo = 0.0, hi = 1.0;
        for (int n = 0; n < 50; ++n) {
          const double mid = 0.5 * (lo + hi);
          ((level(a + (b - a) * mid) < 0.0) == (f0 < 0.0) ? lo : hi) = mid;
        }
        out = a + (b - a) * (0.5 * (lo + hi));
        return true;
      }
      f0 = f1;
    }
  }
  return false;
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
                              double medium_fraction, uint64_t seed, double isosurface) {
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
  const IsosurfaceSampler isosurfaces = isosurface_sampler(scene, isosurface);
  const size_t kinds = surfaces.objects.size() + isosurfaces.objects.size();
  for (int misses = 0; kinds > 0 && int(out.points.size()) < count && misses < count;) {
    // Without isosurfaces no draw is spent on the choice: the mesh probes stay as they were.
    const bool on_volume =
        !isosurfaces.objects.empty() && pick(rng, kinds) >= surfaces.objects.size();
    dvec3 p;
    if (!on_volume)
      p = surface_point(surfaces, rng);
    else if (!isosurface_point(isosurfaces, host, rng, p)) {
      ++misses;
      continue;
    }
    out.points.push_back(p);
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
