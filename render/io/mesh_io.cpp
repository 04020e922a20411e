// Mesh file loading (see mesh_io.h): CGAL::IO::read_polygon_soup parses the formats, then the
// soup is checked (finite coordinates, indices in range, at least triangles) and turned into a
// TriangleMesh.
#include "render/io/mesh_io.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/polygon_soup_io.h>

#include "core/error.h"
#include "core/text.h"
#include "engine/scene/mesh_topology.h"
#include "render/io/mesh_declared_counts.h"

namespace dv {
namespace {

using Point = CGAL::Exact_predicates_inexact_constructions_kernel::Point_3;

constexpr std::array<const char*, 4> kSupportedExtensions = {".obj", ".off", ".ply", ".stl"};

std::string supported_list() {
  std::string list;
  for (const char* ext : kSupportedExtensions)
    list += (list.empty() ? "" : ", ") + std::string(ext);
  return list;
}

[[noreturn]] void unreadable(const std::string& path, const std::string& reason) {
  throw InputError(path, "cannot read mesh file: " + reason);
}

// Fails early with a precise reason for the cases CGAL's readers only answer with "false".
void check_file_readable(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) unreadable(path, "no such file");
  if (!std::filesystem::is_regular_file(path, ec)) unreadable(path, "not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) unreadable(path, "the file cannot be opened (permissions?)");
  auto size = std::filesystem::file_size(path, ec);
  if (ec) unreadable(path, ec.message());
  if (size == 0) unreadable(path, "the file is empty");
}

// CGAL's readers only say whether they succeeded. For OBJ, the common text format, this finds
// the first bad vertex or face line so the message can point at it; "" when none is found.
std::string find_obj_problem(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  size_t total_vertices = 0;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string keyword;
    if (words >> keyword && keyword == "v") ++total_vertices;
  }
  in.clear();
  in.seekg(0);
  size_t line_number = 0, vertices = 0;
  auto at = [&](const std::string& problem) {
    return "line " + std::to_string(line_number) + ": " + problem;
  };
  while (std::getline(in, line)) {
    ++line_number;
    std::istringstream words(line);
    std::string keyword, word;
    if (!(words >> keyword)) continue;
    if (keyword == "v") {
      for (int k = 0; k < 3; ++k) {
        if (!(words >> word)) return at("a vertex needs three coordinates");
        char* end = nullptr;
        const double value = std::strtod(word.c_str(), &end);
        if (end == word.c_str() || *end != '\0') return at("'" + word + "' is not a number");
        if (!std::isfinite(value)) return at("vertex coordinate '" + word + "' is not finite");
      }
      ++vertices;
    } else if (keyword == "f") {
      while (words >> word) {
        const long long index = std::strtoll(word.c_str(), nullptr, 10);  // stops at '/'
        const bool valid =
            index > 0
                ? size_t(index) <= total_vertices
                : index < 0 && index >= -(long long)vertices;  // no negation: strtoll saturates
        if (!valid) {
          return at("face refers to vertex " + word.substr(0, word.find('/')) +
                    " but the file has " + std::to_string(total_vertices) +
                    " vertices (OBJ counts from 1)");
        }
      }
    }
  }
  return "";
}

}  // namespace

bool is_mesh_file(const std::string& path) {
  const std::string ext = lowercase_extension(path);
  return std::find(kSupportedExtensions.begin(), kSupportedExtensions.end(), ext) !=
         kSupportedExtensions.end();
}

TriangleMesh load_mesh_file(const std::string& path) {
  const std::string ext = lowercase_extension(path);
  if (!is_mesh_file(path)) {
    throw InputError(path, "unsupported mesh file extension '" + ext +
                               "' (supported: " + supported_list() + ")");
  }
  check_file_readable(path);
  check_mesh_declared_counts(path, ext);

  std::vector<Point> points;
  std::vector<std::vector<size_t>> polygons;
  bool parsed = false;
  std::string failure = "malformed " + ext.substr(1) +
                        " content (unparsable line or header, no faces, or a face index outside "
                        "the vertex list)";
  try {
    parsed = CGAL::IO::read_polygon_soup(path, points, polygons);
  } catch (const std::exception& e) {
    failure = e.what();
  }
  if (!parsed) {
    const std::string problem = ext == ".obj" ? find_obj_problem(path) : "";
    unreadable(path, problem.empty() ? failure : problem);
  }
  if (points.empty()) unreadable(path, "the file has no vertices");
  if (polygons.empty()) unreadable(path, "the file has no faces");
  if (points.size() >= size_t(UINT32_MAX)) unreadable(path, "too many vertices");

  TriangleMesh mesh;
  mesh.name = path;
  mesh.positions.reserve(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    const Point& p = points[i];
    if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z()))
      throw InputError(path, "vertex " + std::to_string(i) + " is not finite (NaN or Inf)");
    mesh.positions.emplace_back(p.x(), p.y(), p.z());
  }
  mesh.triangles.reserve(polygons.size());
  for (size_t f = 0; f < polygons.size(); ++f) {
    const std::vector<size_t>& face = polygons[f];
    if (face.size() < 3) {
      throw InputError(path, "face " + std::to_string(f) + " has " + std::to_string(face.size()) +
                                 " corner(s); at least 3 are needed");
    }
    for (size_t index : face) {
      if (index >= points.size()) {
        const std::string problem = ext == ".obj" ? find_obj_problem(path) : "";
        if (!problem.empty()) throw InputError(path, problem);
        throw InputError(path, "face " + std::to_string(f) + " refers to vertex index " +
                                   std::to_string(index) + " (0-based) but the file has " +
                                   std::to_string(points.size()) + " vertices");
      }
    }
    for (size_t k = 1; k + 1 < face.size(); ++k)
      mesh.triangles.emplace_back(uint32_t(face[0]), uint32_t(face[k]), uint32_t(face[k + 1]));
  }
  if (ext == ".stl") merge_duplicate_vertices(mesh);
  return mesh;
}

}  // namespace dv
