// Conversion between deepvox's TriangleMesh and CGAL::Surface_mesh, shared by the CGAL-based
// generator and topology code. Internal: only .cpp files of render/load/ include it (CGAL
// headers compile slowly, so public headers stay free of them).
#pragma once

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include <array>
#include <string>
#include <vector>

#include "core/error.h"
#include "engine/scene/scene.h"

namespace dv {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point>;
namespace PMP = CGAL::Polygon_mesh_processing;

inline void check_indices(const TriangleMesh& mesh) {
  const size_t n = mesh.positions.size();
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      if (mesh.triangles[t][k] >= n)
        throw InputError(mesh.name, "triangle " + std::to_string(t) + " uses vertex index " +
                                        std::to_string(mesh.triangles[t][k]) +
                                        " but the mesh has " + std::to_string(n) + " vertices");
    }
  }
}

// Builds a halfedge mesh. Inconsistently wound or non-manifold input is first repaired as a
// polygon soup (CGAL duplicates vertices where a fan cannot be made manifold), so the result
// may have more vertices than the input. Unused vertices and triangles with a repeated corner
// are dropped; otherwise vertex and face order are kept.
inline SurfaceMesh to_surface_mesh(const TriangleMesh& mesh) {
  check_indices(mesh);
  std::vector<Point> points;
  points.reserve(mesh.positions.size());
  for (const dvec3& p : mesh.positions) points.emplace_back(p.x, p.y, p.z);
  std::vector<std::array<size_t, 3>> polygons;
  polygons.reserve(mesh.triangles.size());
  for (const u32vec3& t : mesh.triangles) {
    if (t.x == t.y || t.y == t.z || t.z == t.x) continue;  // no area and no edges to share
    polygons.push_back({t.x, t.y, t.z});
  }
  if (!PMP::is_polygon_soup_a_polygon_mesh(polygons)) PMP::orient_polygon_soup(points, polygons);
  SurfaceMesh surface;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, surface);
  // CGAL keeps unused points as isolated vertices, which its orientation code cannot handle.
  for (SurfaceMesh::Vertex_index v : surface.vertices())
    if (surface.is_isolated(v)) surface.remove_vertex(v);
  surface.collect_garbage();
  return surface;
}

inline TriangleMesh from_surface_mesh(SurfaceMesh& surface, const std::string& name) {
  surface.collect_garbage();
  TriangleMesh out;
  out.name = name;
  out.positions.reserve(surface.number_of_vertices());
  for (SurfaceMesh::Vertex_index v : surface.vertices()) {
    const Point& p = surface.point(v);
    out.positions.emplace_back(p.x(), p.y(), p.z());
  }
  out.triangles.reserve(surface.number_of_faces());
  for (SurfaceMesh::Face_index f : surface.faces()) {
    std::vector<uint32_t> corners;
    for (SurfaceMesh::Vertex_index v : CGAL::vertices_around_face(surface.halfedge(f), surface))
      corners.push_back(uint32_t(v.idx()));
    for (size_t k = 1; k + 1 < corners.size(); ++k)
      out.triangles.emplace_back(corners[0], corners[k], corners[k + 1]);
  }
  return out;
}

}  // namespace dv
