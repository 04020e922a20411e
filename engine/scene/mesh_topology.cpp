// Topology checks and repairs of triangle meshes (see mesh_topology.h). Counting edges and
// merging vertices is plain index work; orientation and hole filling go through a
// CGAL::Surface_mesh (CGAL stays out of the header because its headers compile slowly).
#include "engine/scene/mesh_topology.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>

#include "core/error.h"
#include "engine/scene/cgal_surface_mesh.h"

namespace dv {
namespace {

using Halfedge = SurfaceMesh::Halfedge_index;

// One border halfedge per hole, in halfedge order (deterministic).
std::vector<Halfedge> one_halfedge_per_hole(const SurfaceMesh& surface) {
  std::vector<bool> seen(surface.number_of_halfedges(), false);
  std::vector<Halfedge> holes;
  for (Halfedge h : surface.halfedges()) {
    if (!surface.is_border(h) || seen[h.idx()]) continue;
    holes.push_back(h);
    Halfedge walk = h;
    do {
      seen[walk.idx()] = true;
      walk = surface.next(walk);
    } while (walk != h);
  }
  return holes;
}

// Gives each triangle of `reworked` (the same vertices as `original`, triangles possibly reordered,
// rotated or flipped by CGAL) the corner attributes of the original triangle over the same three
// vertices, each corner following its vertex.
void carry_corner_attributes(const TriangleMesh& original, TriangleMesh& reworked) {
  if (original.corner_uvs.empty() && original.corner_normals.empty()) return;
  auto key = [](const u32vec3& t) {
    std::array<uint32_t, 3> k{t.x, t.y, t.z};
    std::sort(k.begin(), k.end());
    return k;
  };
  std::map<std::array<uint32_t, 3>, size_t> source;
  for (size_t t = 0; t < original.triangles.size(); ++t)
    source.emplace(key(original.triangles[t]), t);
  const bool uvs = !original.corner_uvs.empty(), normals = !original.corner_normals.empty();
  for (const u32vec3& t : reworked.triangles) {
    auto found = source.find(key(t));
    for (int k = 0; k < 3; ++k) {
      size_t from = 0;  // a new triangle (hole filling) takes the first corner's attributes
      if (found != source.end()) {
        const u32vec3& o = original.triangles[found->second];
        const int j = o.x == t[k] ? 0 : o.y == t[k] ? 1 : 2;
        from = 3 * found->second + size_t(j);
      }
      if (uvs) reworked.corner_uvs.push_back(original.corner_uvs[from]);
      if (normals) reworked.corner_normals.push_back(original.corner_normals[from]);
    }
  }
}

size_t border_halfedge_count(const SurfaceMesh& surface) {
  size_t count = 0;
  for (Halfedge h : surface.halfedges()) count += surface.is_border(h) ? 1 : 0;
  return count;
}

}  // namespace

std::vector<OpenEdge> open_edges(const TriangleMesh& mesh) {
  std::vector<uint64_t> keys;
  keys.reserve(mesh.triangles.size() * 3);
  for (const u32vec3& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      uint32_t a = t[k];
      uint32_t b = t[(k + 1) % 3];
      if (a == b) continue;  // collapsed edge of a degenerate triangle
      if (a > b) std::swap(a, b);
      keys.push_back((uint64_t(a) << 32) | b);
    }
  }
  std::sort(keys.begin(), keys.end());
  std::vector<OpenEdge> open;
  for (size_t i = 0; i < keys.size();) {
    size_t j = i;
    while (j < keys.size() && keys[j] == keys[i]) ++j;
    if (j - i != 2) open.push_back({uint32_t(keys[i] >> 32), uint32_t(keys[i] & 0xffffffffu)});
    i = j;
  }
  return open;
}

bool is_closed(const TriangleMesh& mesh) {
  return !mesh.triangles.empty() && open_edges(mesh).empty();
}

double signed_volume(const TriangleMesh& mesh) {
  check_indices(mesh);
  double six_volume = 0.0;
  for (const u32vec3& t : mesh.triangles) {
    const dvec3& a = mesh.positions[t.x];
    const dvec3& b = mesh.positions[t.y];
    const dvec3& c = mesh.positions[t.z];
    six_volume += glm::dot(a, glm::cross(b, c));
  }
  return six_volume / 6.0;
}

void orient_outward(TriangleMesh& mesh) {
  if (mesh.triangles.empty()) return;
  SurfaceMesh surface = to_surface_mesh(mesh);
  // Open meshes have no inside: they only get the consistent winding of to_surface_mesh.
  if (CGAL::is_closed(surface)) PMP::orient_to_bound_a_volume(surface);
  TriangleMesh oriented = from_surface_mesh(surface, mesh.name);
  // Guard for shapes CGAL's nesting test cannot judge (e.g. self-intersecting ones): a closed
  // mesh must never come back with a negative volume.
  if (is_closed(oriented) && signed_volume(oriented) < 0.0) {
    for (u32vec3& t : oriented.triangles) std::swap(t.y, t.z);
  }
  carry_corner_attributes(mesh, oriented);
  mesh = std::move(oriented);
}

void merge_duplicate_vertices(TriangleMesh& mesh) {
  check_indices(mesh);
  auto key = [](const dvec3& p) { return std::make_tuple(p.x, p.y, p.z); };
  std::map<std::tuple<double, double, double>, uint32_t> first_index;
  std::vector<uint32_t> remap(mesh.positions.size());
  std::vector<dvec3> merged;
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const dvec3& p = mesh.positions[i];
    bool finite = std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
    if (finite) {
      auto [it, inserted] = first_index.emplace(key(p), uint32_t(merged.size()));
      remap[i] = it->second;
      if (!inserted) continue;
    } else {
      remap[i] = uint32_t(merged.size());  // NaN cannot be compared: never merged
    }
    merged.push_back(p);
  }
  std::vector<u32vec3> triangles;
  std::vector<dvec2> uvs;
  std::vector<dvec3> normals;
  triangles.reserve(mesh.triangles.size());
  for (size_t i = 0; i < mesh.triangles.size(); ++i) {
    const u32vec3& t = mesh.triangles[i];
    u32vec3 m(remap[t.x], remap[t.y], remap[t.z]);
    // A triangle whose corners collapsed onto each other has no area; keeping it would make
    // its one remaining edge look non-manifold.
    if (m.x == m.y || m.y == m.z || m.z == m.x) continue;
    triangles.push_back(m);
    for (size_t k = 3 * i; k < 3 * i + 3; ++k) {
      if (!mesh.corner_uvs.empty()) uvs.push_back(mesh.corner_uvs[k]);
      if (!mesh.corner_normals.empty()) normals.push_back(mesh.corner_normals[k]);
    }
  }
  mesh.positions = std::move(merged);
  mesh.triangles = std::move(triangles);
  mesh.corner_uvs = std::move(uvs);
  mesh.corner_normals = std::move(normals);
}

void close_holes(TriangleMesh& mesh) {
  if (mesh.triangles.empty()) throw Error(mesh.name + ": cannot close the holes of an empty mesh");
  SurfaceMesh surface = to_surface_mesh(mesh);
  for (Halfedge h : one_halfedge_per_hole(surface)) {
    std::vector<SurfaceMesh::Face_index> patch_faces;
    std::vector<SurfaceMesh::Vertex_index> patch_vertices;
    PMP::triangulate_refine_and_fair_hole(surface, h, std::back_inserter(patch_faces),
                                          std::back_inserter(patch_vertices));
    // Fairing may fail (singular system); the refined patch is still in place, only not smooth.
  }
  if (!CGAL::is_closed(surface)) {
    throw Error(mesh.name + ": hole filling left " +
                std::to_string(border_halfedge_count(surface)) + " border edge(s) open");
  }
  PMP::orient_to_bound_a_volume(surface);
  TriangleMesh closed = from_surface_mesh(surface, mesh.name);
  if (!is_closed(closed)) {
    throw Error(mesh.name + ": hole filling did not produce a closed mesh (" +
                std::to_string(open_edges(closed).size()) + " open edge(s))");
  }
  if (signed_volume(closed) < 0.0) {
    for (u32vec3& t : closed.triangles) std::swap(t.y, t.z);
  }
  carry_corner_attributes(mesh, closed);
  mesh = std::move(closed);
}

}  // namespace dv
