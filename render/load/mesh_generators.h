// Deterministic, parameterised triangle-mesh generators (boxes, spheres, a teacup, the shared
// bunny scan, ...) and subdivision, so scenes and experiments can name test geometry by its
// parameters instead of shipping mesh files. Every generator returns a closed mesh with outward
// normals (positive signed volume) unless noted; the same parameters always give the same
// vertex and triangle arrays.
//
// JSON parameters of generate_mesh (all optional unless stated; lengths in object units):
//
//   "generator": one of the names below (required).
//
//   box             "min": [x,y,z] = [-0.5,-0.5,-0.5], "max": [x,y,z] = [0.5,0.5,0.5]
//                   or instead "size": edge length of a cube centred at the origin.
//                   8 vertices, 12 triangles.
//   quad            "size" = 1. Square in the y = 0 plane centred at the origin, normal +y.
//                   OPEN: 4 vertices, 2 triangles.
//   subdivided_quad "size" = 1, "target_triangles" = 11858. Same square as "quad" cut into an
//                   nx x nz grid of cells, two triangles per cell. OPEN. The grid is the one
//                   whose count 2*nx*nz lies closest to the target, among grids with
//                   nx <= nz <= 2*nx (cells at most twice as long as wide); ties go to the more
//                   square grid. Every even target whose half factors that way is hit exactly:
//                   11858 = 2 * 77 * 77 gives 77 x 77 cells. An odd target rounds to an even
//                   neighbour.
//   icosphere       "radius" = 0.5, "subdivisions" = 3. Icosahedron whose faces are split into
//                   4 (edge midpoints pushed onto the sphere) per subdivision:
//                   20 * 4^subdivisions triangles.
//   uv_sphere       "radius" = 0.5, "segments" = 32 (around y, >= 3), "rings" = 16 (pole to
//                   pole, >= 2). Single vertices at the poles: 2 * segments * (rings - 1)
//                   triangles.
//   cylinder        "radius" = 0.5, "height" = 1, "segments" = 32 (>= 3). Axis y, centred at
//                   the origin, capped with fans around a centre vertex: 4 * segments triangles.
//   torus           "major_radius" = 0.35, "minor_radius" = 0.15 (< major_radius),
//                   "segments" = 48 (around y, >= 3), "sides" = 24 (around the tube, >= 3).
//                   Axis y: 2 * segments * sides triangles.
//   cup             "radius" = 0.5 (outer radius at the rim), "bottom_radius" = 0.35 (outer
//                   radius at the foot), "height" = 0.8, "wall" = 0.04 (wall thickness),
//                   "bottom" = 0.06 (thickness of the floor), "segments" = 64 (>= 3),
//                   "profile_samples" = 16 (points along each wall, >= 2). A teacup-like solid
//                   of revolution about y standing on y = 0: the closed profile runs from the
//                   foot centre out along the foot, up the flared outer wall, across the flat
//                   rim, down the inner wall and in along the floor to the axis.
//                   4 * segments * profile_samples triangles.
//   bunny           "subdivisions" = 0 (midpoint subdivisions). The shared Stanford bunny scan
//                   <assets_dir>/meshes/stanford-bunny-lowres.obj, holes closed, oriented
//                   outward, then midpoint-subdivided. The file as shipped is already closed
//                   (3,674 triangles, 1,839 vertices), so the counts are 3,674 * 4^n:
//                   3,674 / 14,696 / 58,784 / 235,136 for n = 0..3.
//
//   "subdivide" (any generator): {"scheme": "loop" | "sqrt3" | "midpoint", "iterations": N}
//                   or {"scheme": ..., "target_triangles": N} (subdivide until the count
//                   reaches N). loop and midpoint multiply the triangle count by 4 per
//                   iteration, sqrt3 by 3 (on closed meshes).
//
// Every generator refuses to build more than kMaxGeneratedTriangles triangles.
#pragma once

#include <string>
#include <vector>

#include "core/json_reader.h"
#include "engine/scene/scene.h"

namespace dv {

inline constexpr long long kMaxGeneratedTriangles = 20'000'000;

TriangleMesh make_box(dvec3 lo, dvec3 hi);
TriangleMesh make_quad(double size);
TriangleMesh make_subdivided_quad(double size, int target_triangles);
TriangleMesh make_icosphere(double radius, int subdivisions);
TriangleMesh make_uv_sphere(double radius, int segments, int rings);
TriangleMesh make_cylinder(double radius, double height, int segments);
TriangleMesh make_torus(double major_radius, double minor_radius, int segments, int sides);

struct CupShape {
  double radius = 0.5;          // outer radius at the rim
  double bottom_radius = 0.35;  // outer radius at the foot
  double height = 0.8;
  double wall = 0.04;    // wall thickness (measured horizontally)
  double bottom = 0.06;  // floor thickness
  int segments = 64;
  int profile_samples = 16;
};
TriangleMesh make_cup(const CupShape& shape);

enum class SubdivisionScheme { loop, sqrt3, midpoint };

// loop and sqrt3 use CGAL::Subdivision_method_3 (vertices move towards a smooth limit surface);
// midpoint splits every triangle into 4 at its edge midpoints and moves nothing, so the shape
// and a closed mesh's closedness are kept exactly.
TriangleMesh subdivide(const TriangleMesh& mesh, SubdivisionScheme scheme, int iterations);
// Subdivides until the triangle count is >= target (no iteration when it already is).
TriangleMesh subdivide_to_count(const TriangleMesh& mesh, SubdivisionScheme scheme,
                                long long target);

// The shared bunny scan (see "bunny" above); assets_dir is the folder that holds meshes/.
TriangleMesh make_bunny(const std::string& assets_dir, int midpoint_iterations);

// Builds the mesh a JSON spec describes (see the table above) and calls spec.finish(); bad
// values and unknown keys or generators are InputErrors naming the JSON path.
TriangleMesh generate_mesh(JsonReader& spec, const std::string& assets_dir);
std::vector<std::string> mesh_generator_names();

}  // namespace dv
