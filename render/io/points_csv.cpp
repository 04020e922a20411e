// CSV input and output of `deepvox probe` (see points_csv.h).
#include "render/io/points_csv.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "core/error.h"

namespace dv {

namespace {

// Parses "x,y,z" (spaces allowed around fields); returns false if any field is not a number.
bool parse_row(const std::string& line, dvec3& out) {
  std::stringstream ss(line);
  std::string field;
  int k = 0;
  while (std::getline(ss, field, ',')) {
    if (k >= 3) return false;
    const char* begin = field.c_str();
    char* end = nullptr;
    errno = 0;
    double v = std::strtod(begin, &end);
    while (*end == ' ' || *end == '\t' || *end == '\r') ++end;
    if (end == begin || *end != '\0' || errno == ERANGE) return false;
    out[k++] = v;
  }
  return k == 3;
}

bool blank(const std::string& line) {
  return line.find_first_not_of(" \t\r") == std::string::npos;
}

}  // namespace

std::vector<dvec3> read_points_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "cannot open points file");
  std::vector<dvec3> points;
  std::string line;
  int line_no = 0;
  bool first = true;
  while (std::getline(in, line)) {
    ++line_no;
    if (blank(line)) continue;
    dvec3 p;
    if (!parse_row(line, p)) {
      if (first) {  // a header line such as "x,y,z"
        first = false;
        continue;
      }
      throw InputError(path + ":" + std::to_string(line_no), "expected three numbers x,y,z");
    }
    first = false;
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw InputError(path + ":" + std::to_string(line_no), "point is not finite");
    points.push_back(p);
  }
  return points;
}

void write_transmittance_csv(const std::string& path, const std::vector<dvec3>& points,
                             const std::vector<double>& values, const std::vector<dvec3>& rgb,
                             int light_count) {
  std::ofstream out(path);
  if (!out) throw InputError(path, "cannot open output file for writing");
  out << "x,y,z";
  for (int l = 0; l < light_count; ++l) out << ",light" << l;
  for (int l = 0; l < light_count; ++l)
    out << ",light" << l << "_r,light" << l << "_g,light" << l << "_b";
  out << "\n";
  // The shortest text that reads back as the same double (0.148, not 0.14799999999999999).
  char buf[64];
  auto put = [&](double v) {
    const std::to_chars_result written = std::to_chars(buf, buf + sizeof buf, v);
    out.write(buf, written.ptr - buf);
  };
  for (size_t i = 0; i < points.size(); ++i) {
    put(points[i].x), out << ",", put(points[i].y), out << ",", put(points[i].z);
    for (int l = 0; l < light_count; ++l) out << ",", put(values[i * light_count + l]);
    for (int l = 0; l < light_count; ++l) {
      const dvec3& c = rgb[i * light_count + l];
      out << ",", put(c.x), out << ",", put(c.y), out << ",", put(c.z);
    }
    out << "\n";
  }
  if (!out) throw InputError(path, "write failed");
}

}  // namespace dv
