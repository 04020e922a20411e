// Loading triangle meshes from OBJ, OFF, PLY and STL files (CGAL's polygon-soup readers), with
// every problem of the file reported as an InputError that names it.
#pragma once

#include <string>

#include "engine/scene/scene.h"

namespace dv {

// Reads the file's vertices and faces. Polygons with more than three corners are split into
// a fan around their first corner (right for the convex faces exporters write); faces with
// fewer than three corners, indices out of range and NaN/Inf coordinates are errors. STL
// files repeat each corner per facet, so their identical positions are merged. The mesh is
// named after the path. Normals, texture coordinates and colours are ignored.
TriangleMesh load_mesh_file(const std::string& path);

// True when the extension is one load_mesh_file reads (.obj .off .ply .stl, any letter case).
bool is_mesh_file(const std::string& path);

}  // namespace dv
