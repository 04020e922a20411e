// Topology checks and repairs on triangle meshes: open edges (the error message for interiors
// on open meshes lists them), outward orientation of closed meshes (the oracle's chord
// formula relies on it), and hole filling so an open scan becomes a closed solid.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/scene/scene.h"

namespace dv {

// An undirected edge (a < b) not shared by exactly two triangles.
struct OpenEdge {
  uint32_t a = 0;
  uint32_t b = 0;
};

// Edges used by one triangle, or by more than two (non-manifold). Vertices are compared by
// index; loaders merge duplicate positions first.
std::vector<OpenEdge> open_edges(const TriangleMesh& mesh);
bool is_closed(const TriangleMesh& mesh);

// Signed volume (positive when normals point outward).
double signed_volume(const TriangleMesh& mesh);

// Makes a closed mesh's triangle winding consistent with outward normals (CGAL orientation).
void orient_outward(TriangleMesh& mesh);

// Merges vertices with identical positions (STL and OBJ soups repeat them).
void merge_duplicate_vertices(TriangleMesh& mesh);

// Fills every hole (CGAL triangulate_refine_and_fair_hole or triangulate_hole) and orients
// the result outward; afterwards is_closed(mesh) holds or an Error is thrown.
void close_holes(TriangleMesh& mesh);

}  // namespace dv
