// Mesh generators and subdivision (see mesh_generators.h for the shapes and their parameters).
// Round shapes come from one routine that revolves a 2D profile about the y axis; loop and
// sqrt3 subdivision go through CGAL::Subdivision_method_3, midpoint subdivision is our own.
#include "render/load/mesh_generators.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <unordered_map>

#include <CGAL/Subdivision_method_3/subdivision_methods_3.h>

#include "core/error.h"
#include "engine/scene/cgal_surface_mesh.h"
#include "engine/scene/mesh_topology.h"
#include "render/io/mesh_io.h"

namespace dv {
namespace {

void require(bool ok, const std::string& generator, const std::string& problem) {
  if (!ok) throw InputError(generator, problem);
}

void require_triangle_budget(double triangles, const std::string& generator) {
  if (triangles <= double(kMaxGeneratedTriangles)) return;
  char count[32];  // the count may exceed every integer type (found by fuzz_scene_json)
  std::snprintf(count, sizeof count, "%.4g", triangles);
  throw InputError(generator, std::string("would build ") + count + " triangles, more than the " +
                                  std::to_string(kMaxGeneratedTriangles) + " allowed");
}

// A grid of nx by nz cells over the square [-size/2, size/2]^2 in y = 0, normals +y.
TriangleMesh make_grid(const std::string& name, double size, int nx, int nz) {
  TriangleMesh mesh;
  mesh.name = name;
  const double half = 0.5 * size;
  for (int k = 0; k <= nz; ++k) {
    for (int i = 0; i <= nx; ++i)
      mesh.positions.emplace_back(-half + size * i / nx, 0.0, -half + size * k / nz);
  }
  auto at = [nx](int i, int k) { return uint32_t(k * (nx + 1) + i); };
  for (int k = 0; k < nz; ++k) {
    for (int i = 0; i < nx; ++i) {
      mesh.triangles.emplace_back(at(i, k), at(i, k + 1), at(i + 1, k + 1));
      mesh.triangles.emplace_back(at(i, k), at(i + 1, k + 1), at(i + 1, k));
    }
  }
  return mesh;
}

// Revolves a profile of (radius, y) points about the y axis. The profile must run
// counter-clockwise in the (radius, y) half-plane (the solid's cross-section on its left) so
// that the normals point outward. Open profiles must start and end on the axis (radius 0),
// where a single pole vertex is made; closed_loop profiles (a torus tube) wrap around.
TriangleMesh revolve(const std::string& name, const std::vector<dvec2>& profile, int segments,
                     bool closed_loop) {
  TriangleMesh mesh;
  mesh.name = name;
  const size_t n = profile.size();
  std::vector<uint32_t> first_vertex(n);
  auto is_pole = [&](size_t i) { return !closed_loop && profile[i].x == 0.0; };
  for (size_t i = 0; i < n; ++i) {
    first_vertex[i] = uint32_t(mesh.positions.size());
    if (is_pole(i)) {
      mesh.positions.emplace_back(0.0, profile[i].y, 0.0);
      continue;
    }
    for (int j = 0; j < segments; ++j) {
      const double angle = 2.0 * std::numbers::pi * j / segments;
      mesh.positions.emplace_back(profile[i].x * std::cos(angle), profile[i].y,
                                  profile[i].x * std::sin(angle));
    }
  }
  auto vertex = [&](size_t i, int j) {
    return is_pole(i) ? first_vertex[i] : first_vertex[i] + uint32_t(j % segments);
  };
  const size_t spans = closed_loop ? n : n - 1;
  for (size_t i = 0; i < spans; ++i) {
    const size_t next = (i + 1) % n;
    for (int j = 0; j < segments; ++j) {
      const uint32_t a = vertex(i, j), b = vertex(next, j);
      const uint32_t c = vertex(next, j + 1), d = vertex(i, j + 1);
      if (is_pole(i)) {
        mesh.triangles.emplace_back(a, b, c);
      } else if (is_pole(next)) {
        mesh.triangles.emplace_back(a, b, d);
      } else {
        mesh.triangles.emplace_back(a, b, c);
        mesh.triangles.emplace_back(a, c, d);
      }
    }
  }
  return mesh;
}

TriangleMesh midpoint_subdivide_once(const TriangleMesh& mesh) {
  TriangleMesh out;
  out.name = mesh.name;
  out.positions = mesh.positions;
  std::unordered_map<uint64_t, uint32_t> midpoint_of_edge;
  auto midpoint = [&](uint32_t a, uint32_t b) {
    const uint64_t key = (uint64_t(std::min(a, b)) << 32) | std::max(a, b);
    auto [it, inserted] = midpoint_of_edge.emplace(key, uint32_t(out.positions.size()));
    if (inserted) out.positions.push_back(0.5 * (mesh.positions[a] + mesh.positions[b]));
    return it->second;
  };
  out.triangles.reserve(mesh.triangles.size() * 4);
  for (const u32vec3& t : mesh.triangles) {
    const uint32_t ab = midpoint(t.x, t.y), bc = midpoint(t.y, t.z), ca = midpoint(t.z, t.x);
    out.triangles.emplace_back(t.x, ab, ca);
    out.triangles.emplace_back(ab, t.y, bc);
    out.triangles.emplace_back(ca, bc, t.z);
    out.triangles.emplace_back(ab, bc, ca);
  }
  return out;
}

TriangleMesh cgal_subdivide(const TriangleMesh& mesh, SubdivisionScheme scheme, int iterations) {
  SurfaceMesh surface = to_surface_mesh(mesh);
  const auto steps = CGAL::parameters::number_of_iterations(unsigned(iterations));
  if (scheme == SubdivisionScheme::loop) {
    CGAL::Subdivision_method_3::Loop_subdivision(surface, steps);
  } else {
    CGAL::Subdivision_method_3::Sqrt3_subdivision(surface, steps);
  }
  return from_surface_mesh(surface, mesh.name);
}

double growth_factor(SubdivisionScheme scheme) {
  return scheme == SubdivisionScheme::sqrt3 ? 3.0 : 4.0;
}

SubdivisionScheme parse_scheme(JsonReader& spec) {
  const std::string name = spec.string("scheme");
  if (name == "loop") return SubdivisionScheme::loop;
  if (name == "sqrt3") return SubdivisionScheme::sqrt3;
  if (name == "midpoint") return SubdivisionScheme::midpoint;
  spec.fail("scheme", "unknown subdivision scheme '" + name + "' (known: loop, sqrt3, midpoint)");
}

}  // namespace

TriangleMesh make_box(dvec3 lo, dvec3 hi) {
  require(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z, "box",
          "'min' must be below 'max' on every axis");
  TriangleMesh mesh;
  mesh.name = "box";
  for (int i = 0; i < 8; ++i)  // corner i has x from bit 0, y from bit 1, z from bit 2
    mesh.positions.emplace_back(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
  // Faces -x, +x, -y, +y, -z, +z, corners counter-clockwise seen from outside.
  const int faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (const auto& q : faces) {
    mesh.triangles.emplace_back(q[0], q[1], q[2]);
    mesh.triangles.emplace_back(q[0], q[2], q[3]);
  }
  return mesh;
}

TriangleMesh make_quad(double size) {
  require(size > 0.0, "quad", "'size' must be positive");
  return make_grid("quad", size, 1, 1);
}

TriangleMesh make_subdivided_quad(double size, int target_triangles) {
  require(size > 0.0, "subdivided_quad", "'size' must be positive");
  require(target_triangles >= 2, "subdivided_quad", "'target_triangles' must be at least 2");
  require_triangle_budget(target_triangles, "subdivided_quad");
  const long long cells = (target_triangles + 1) / 2;
  long long best_nx = 1, best_nz = 1, best_miss = cells - 1;
  for (long long nx = 1; (nx - 1) * (nx - 1) <= cells; ++nx) {
    for (long long nz : {cells / nx, cells / nx + 1}) {
      nz = std::clamp(nz, nx, 2 * nx);
      const long long miss = std::llabs(nx * nz - cells);
      if (miss < best_miss || (miss == best_miss && nz - nx < best_nz - best_nx)) {
        best_miss = miss;
        best_nx = nx;
        best_nz = nz;
      }
    }
  }
  return make_grid("subdivided_quad", size, int(best_nx), int(best_nz));
}

TriangleMesh make_icosphere(double radius, int subdivisions) {
  require(radius > 0.0, "icosphere", "'radius' must be positive");
  require(subdivisions >= 0, "icosphere", "'subdivisions' must be >= 0");
  require_triangle_budget(20.0 * std::pow(4.0, subdivisions), "icosphere");
  // Icosahedron: cyclic permutations of (0, +-1, +-phi); its edges are the vertex pairs at
  // distance 2, its faces the triples of mutually adjacent vertices.
  const double phi = 0.5 * (1.0 + std::sqrt(5.0));
  TriangleMesh mesh;
  mesh.name = "icosphere";
  for (int axis = 0; axis < 3; ++axis) {
    for (double s1 : {-1.0, 1.0}) {
      for (double s2 : {-phi, phi}) {
        dvec3 p(0.0);
        p[(axis + 1) % 3] = s1;
        p[(axis + 2) % 3] = s2;
        mesh.positions.push_back(p);
      }
    }
  }
  auto adjacent = [&](int i, int j) {
    return std::abs(glm::distance(mesh.positions[i], mesh.positions[j]) - 2.0) < 1e-9;
  };
  for (int i = 0; i < 12; ++i) {
    for (int j = i + 1; j < 12; ++j) {
      for (int k = j + 1; k < 12; ++k) {
        if (!adjacent(i, j) || !adjacent(j, k) || !adjacent(i, k)) continue;
        const dvec3 &a = mesh.positions[i], &b = mesh.positions[j], &c = mesh.positions[k];
        const bool outward = glm::dot(glm::cross(b - a, c - a), a + b + c) > 0.0;
        mesh.triangles.push_back(outward ? u32vec3(i, j, k) : u32vec3(i, k, j));
      }
    }
  }
  for (dvec3& p : mesh.positions) p = glm::normalize(p);
  for (int s = 0; s < subdivisions; ++s) {
    mesh = midpoint_subdivide_once(mesh);
    for (dvec3& p : mesh.positions) p = glm::normalize(p);
  }
  for (dvec3& p : mesh.positions) p *= radius;
  return mesh;
}

TriangleMesh make_uv_sphere(double radius, int segments, int rings) {
  require(radius > 0.0, "uv_sphere", "'radius' must be positive");
  require(segments >= 3, "uv_sphere", "'segments' must be at least 3");
  require(rings >= 2, "uv_sphere", "'rings' must be at least 2");
  require_triangle_budget(2.0 * segments * (rings - 1.0), "uv_sphere");
  std::vector<dvec2> profile{{0.0, -radius}};
  for (int i = 1; i < rings; ++i) {
    const double angle = std::numbers::pi * (double(i) / rings - 0.5);
    profile.emplace_back(radius * std::cos(angle), radius * std::sin(angle));
  }
  profile.emplace_back(0.0, radius);
  return revolve("uv_sphere", profile, segments, false);
}

TriangleMesh make_cylinder(double radius, double height, int segments) {
  require(radius > 0.0 && height > 0.0, "cylinder", "'radius' and 'height' must be positive");
  require(segments >= 3, "cylinder", "'segments' must be at least 3");
  require_triangle_budget(4.0 * segments, "cylinder");
  const double h = 0.5 * height;
  return revolve("cylinder", {{0.0, -h}, {radius, -h}, {radius, h}, {0.0, h}}, segments, false);
}

TriangleMesh make_torus(double major_radius, double minor_radius, int segments, int sides) {
  require(minor_radius > 0.0 && minor_radius < major_radius, "torus",
          "need 0 < 'minor_radius' < 'major_radius'");
  require(segments >= 3 && sides >= 3, "torus", "'segments' and 'sides' must be at least 3");
  require_triangle_budget(2.0 * segments * sides, "torus");
  std::vector<dvec2> tube;
  for (int i = 0; i < sides; ++i) {
    const double angle = 2.0 * std::numbers::pi * i / sides;
    tube.emplace_back(major_radius + minor_radius * std::cos(angle),
                      minor_radius * std::sin(angle));
  }
  return revolve("torus", tube, segments, true);
}

TriangleMesh make_cup(const CupShape& cup) {
  require(cup.radius > 0.0 && cup.bottom_radius > 0.0 && cup.height > 0.0, "cup",
          "'radius', 'bottom_radius' and 'height' must be positive");
  require(cup.wall > 0.0 && cup.wall < std::min(cup.radius, cup.bottom_radius), "cup",
          "'wall' must be positive and thinner than 'radius' and 'bottom_radius'");
  require(cup.bottom > 0.0 && cup.bottom < cup.height, "cup",
          "'bottom' must be positive and below 'height'");
  require(cup.segments >= 3, "cup", "'segments' must be at least 3");
  require(cup.profile_samples >= 2, "cup", "'profile_samples' must be at least 2");
  require_triangle_budget(4.0 * cup.segments * cup.profile_samples, "cup");
  // Outer radius at height y: flares quickly above the foot, then straightens to the rim.
  auto outer_radius = [&](double y) {
    const double t = 1.0 - y / cup.height;
    return cup.bottom_radius + (cup.radius - cup.bottom_radius) * (1.0 - t * t);
  };
  const int n = cup.profile_samples;
  std::vector<dvec2> profile{{0.0, 0.0}};
  for (int i = 0; i < n; ++i) {
    const double y = cup.height * i / (n - 1);
    profile.emplace_back(outer_radius(y), y);
  }
  for (int i = 0; i < n; ++i) {
    const double y = cup.height - (cup.height - cup.bottom) * i / (n - 1);
    profile.emplace_back(outer_radius(y) - cup.wall, y);
  }
  profile.emplace_back(0.0, cup.bottom);
  return revolve("cup", profile, cup.segments, false);
}

TriangleMesh subdivide(const TriangleMesh& mesh, SubdivisionScheme scheme, int iterations) {
  require(iterations >= 0, "subdivide", "'iterations' must be >= 0");
  require_triangle_budget(
      double(mesh.triangles.size()) * std::pow(growth_factor(scheme), iterations), "subdivide");
  if (iterations == 0) return mesh;
  if (scheme != SubdivisionScheme::midpoint) return cgal_subdivide(mesh, scheme, iterations);
  for (const u32vec3& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k)
      require(t[k] < mesh.positions.size(), mesh.name, "triangle index out of range");
  }
  TriangleMesh out = mesh;
  for (int i = 0; i < iterations; ++i) out = midpoint_subdivide_once(out);
  return out;
}

TriangleMesh subdivide_to_count(const TriangleMesh& mesh, SubdivisionScheme scheme,
                                long long target) {
  require(target <= kMaxGeneratedTriangles, "subdivide",
          "'target_triangles' is above the limit of " + std::to_string(kMaxGeneratedTriangles));
  TriangleMesh out = mesh;
  while ((long long)out.triangles.size() < target) {
    require(!out.triangles.empty(), "subdivide", "cannot subdivide a mesh without triangles");
    out = subdivide(out, scheme, 1);
  }
  return out;
}

TriangleMesh make_bunny(const std::string& assets_dir, int midpoint_iterations) {
  require(midpoint_iterations >= 0, "bunny", "'subdivisions' must be >= 0");
  TriangleMesh mesh = load_mesh_file(assets_dir + "/meshes/stanford-bunny-lowres.obj");
  if (is_closed(mesh)) {
    orient_outward(mesh);
  } else {
    close_holes(mesh);
  }
  mesh = subdivide(mesh, SubdivisionScheme::midpoint, midpoint_iterations);
  mesh.name = "bunny";
  return mesh;
}

std::vector<std::string> mesh_generator_names() {
  return {"box", "quad", "subdivided_quad", "icosphere", "uv_sphere", "cylinder", "torus",
          "cup", "bunny"};
}

TriangleMesh generate_mesh(JsonReader& spec, const std::string& assets_dir) {
  const std::string generator = spec.string("generator");
  std::function<TriangleMesh()> build;
  if (generator == "box") {
    if (spec.has("size")) {
      if (spec.has("min") || spec.has("max"))
        spec.fail("size", "give 'size' or 'min'/'max', not both");
      const double size = spec.number("size");
      if (!(size > 0.0)) spec.fail("size", "must be positive");
      const double half = 0.5 * size;
      build = [half] { return make_box(dvec3(-half), dvec3(half)); };
    } else {
      const dvec3 lo = spec.vec3("min", dvec3(-0.5)), hi = spec.vec3("max", dvec3(0.5));
      build = [lo, hi] { return make_box(lo, hi); };
    }
  } else if (generator == "quad") {
    const double size = spec.number("size", 1.0);
    build = [size] { return make_quad(size); };
  } else if (generator == "subdivided_quad") {
    const double size = spec.number("size", 1.0);
    const int target = spec.integer("target_triangles", 11858);
    build = [size, target] { return make_subdivided_quad(size, target); };
  } else if (generator == "icosphere") {
    const double radius = spec.number("radius", 0.5);
    const int subdivisions = spec.integer("subdivisions", 3);
    build = [radius, subdivisions] { return make_icosphere(radius, subdivisions); };
  } else if (generator == "uv_sphere") {
    const double radius = spec.number("radius", 0.5);
    const int segments = spec.integer("segments", 32), rings = spec.integer("rings", 16);
    build = [=] { return make_uv_sphere(radius, segments, rings); };
  } else if (generator == "cylinder") {
    const double radius = spec.number("radius", 0.5), height = spec.number("height", 1.0);
    const int segments = spec.integer("segments", 32);
    build = [=] { return make_cylinder(radius, height, segments); };
  } else if (generator == "torus") {
    const double major = spec.number("major_radius", 0.35);
    const double minor = spec.number("minor_radius", 0.15);
    const int segments = spec.integer("segments", 48), sides = spec.integer("sides", 24);
    build = [=] { return make_torus(major, minor, segments, sides); };
  } else if (generator == "cup") {
    CupShape cup;
    cup.radius = spec.number("radius", cup.radius);
    cup.bottom_radius = spec.number("bottom_radius", cup.bottom_radius);
    cup.height = spec.number("height", cup.height);
    cup.wall = spec.number("wall", cup.wall);
    cup.bottom = spec.number("bottom", cup.bottom);
    cup.segments = spec.integer("segments", cup.segments);
    cup.profile_samples = spec.integer("profile_samples", cup.profile_samples);
    build = [cup] { return make_cup(cup); };
  } else if (generator == "bunny") {
    const int iterations = spec.integer("subdivisions", 0);
    build = [assets_dir, iterations] { return make_bunny(assets_dir, iterations); };
  } else {
    std::string known;
    for (const std::string& name : mesh_generator_names())
      known += (known.empty() ? "" : ", ") + name;
    spec.fail("generator", "unknown generator '" + generator + "' (known: " + known + ")");
  }

  std::function<TriangleMesh(const TriangleMesh&)> refine;
  if (spec.has("subdivide")) {
    JsonReader sub = spec.child("subdivide");
    const SubdivisionScheme scheme = parse_scheme(sub);
    if (sub.has("iterations") == sub.has("target_triangles"))
      sub.fail("", "give exactly one of 'iterations' or 'target_triangles'");
    if (sub.has("iterations")) {
      const int iterations = sub.integer("iterations");
      refine = [=](const TriangleMesh& m) { return subdivide(m, scheme, iterations); };
    } else {
      const int target = sub.integer("target_triangles");
      refine = [=](const TriangleMesh& m) { return subdivide_to_count(m, scheme, target); };
    }
    sub.finish();
  }
  spec.finish();

  try {
    TriangleMesh mesh = build();
    return refine ? refine(mesh) : mesh;
  } catch (const InputError& e) {
    throw InputError(spec.where(), e.what());
  }
}

}  // namespace dv
