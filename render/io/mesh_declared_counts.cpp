// OFF and PLY declared counts against the file's contents (see mesh_declared_counts.h).
#include "render/io/mesh_declared_counts.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <vector>

#include "core/error.h"

namespace dv {
namespace {

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::string> split_words(const std::string& line) {
  std::vector<std::string> words;
  std::istringstream in(line.substr(0, line.find('#')));
  for (std::string w; in >> w;) words.push_back(w);
  return words;
}

// A count as a non-negative integer, or -1 when the word is not one.
long long count_of(const std::string& word) {
  if (word.empty() || word.size() > 18) return -1;
  for (char c : word)
    if (c < '0' || c > '9') return -1;
  return std::stoll(word);
}

// ASCII OFF: "[C|N|ST|4|n]OFF", the counts (read as CGAL's stream reads them, over as many
// lines as they take), vertex lines (one vertex a line, at least 3 numbers), then face lines
// "k i1 .. ik [colour]": k a count no larger than the numbers left in the file, each index a
// vertex.
void check_off(const std::string& path, const std::string& text) {
  // CGAL's binary OFF reader converts header floats to int without a range check (UB; found
  // by fuzz_mesh, also with NUL bytes between the keywords): binary OFF is not read.
  const std::string first_line = text.substr(0, text.find('\n', text.find_first_not_of("\r\n \t")));
  if (first_line.find("OFF") != std::string::npos && first_line.find("BINARY") != std::string::npos)
    throw InputError(path, "binary OFF is not read: convert it to ASCII OFF or PLY");
  std::vector<std::vector<std::string>> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> words = split_words(line);
    if (!words.empty()) lines.push_back(std::move(words));
  }
  if (lines.empty()) return;
  // CGAL's keyword is the first word's letters and digits; the character ending them is
  // consumed and the counts follow it ("OFF=9 9 0" is OFF: fuzz_mesh).
  const std::string& head = lines[0][0];
  const size_t end = size_t(std::find_if(head.begin(), head.end(),
                                         [](char c) { return !std::isalnum((unsigned char)c); }) -
                            head.begin());
  const std::string keyword = head.substr(0, end);
  if (keyword.size() < 3 || keyword.compare(keyword.size() - 3, 3, "OFF") != 0)
    return;  // not OFF: CGAL's reader names the problem
  // CGAL reads the counts as integer extractions from the stream after the keyword, over as
  // many lines as it takes ("2000-00000" is 2000, then -0; "OFF\n2000000000\n20000 0":
  // fuzz_mesh). Read them the same way; vertex lines start on the line after the last count.
  std::string stream_text = end + 1 < head.size() ? head.substr(end + 1) : "";
  for (size_t w = 1; w < lines[0].size(); ++w) stream_text += " " + lines[0][w];
  std::vector<size_t> line_starts;  // of lines[1], lines[2], ... in stream_text
  for (size_t i = 1; i < lines.size(); ++i) {
    stream_text += "\n";
    line_starts.push_back(stream_text.size());
    for (const std::string& word : lines[i]) stream_text += word + " ";
  }
  std::istringstream numbers(stream_text);
  std::string first_word;
  if (std::istringstream(stream_text) >> first_word && first_word == "BINARY") return;  // refused
  long long vertices = -1, faces = -1, edges = 0;
  if (!(numbers >> vertices >> faces) || vertices < 0 || faces < 0) return;  // CGAL refuses it
  std::streamoff consumed = numbers.tellg();
  // CGAL doubles the edge count into an int unchecked (UB above 2^30: fuzz_mesh).
  if (numbers >> edges) {
    if (edges < 0 || edges > (1ll << 30))
      throw InputError(
          path, "the header declares " + std::to_string(edges) + " edges, outside [0, 2^30]");
    consumed = numbers.tellg();
  }
  size_t next = 1;
  while (next - 1 < line_starts.size() && std::streamoff(line_starts[next - 1]) <= consumed) ++next;
  long long words_left = 0;  // numbers after the counts
  for (size_t i = next; i < lines.size(); ++i) words_left += (long long)lines[i].size();
  if (vertices > words_left / 3 || faces > words_left - 3 * vertices)
    throw InputError(path, "the header declares " + std::to_string(vertices) + " vertices and " +
                               std::to_string(faces) + " faces, but the file holds only " +
                               std::to_string(words_left) + " numbers after it");
  // One vertex per line (the usual layout): then the face lines follow them (those present:
  // CGAL reads the first ones before it finds the rest missing).
  if ((long long)(lines.size() - next) < vertices) return;
  for (long long v = 0; v < vertices; ++v) {
    words_left -= (long long)lines[next + size_t(v)].size();
    if (lines[next + size_t(v)].size() < 3)  // CGAL reads on into the faces (fuzz_mesh)
      throw InputError(path, "vertex " + std::to_string(v) +
                                 ": fewer than 3 numbers on its line (one vertex a line)");
  }
  const long long face_lines =
      std::min<long long>(faces, (long long)(lines.size() - next) - vertices);
  for (long long f = 0; f < face_lines; ++f) {
    const std::vector<std::string>& face = lines[next + size_t(vertices + f)];
    const long long corners = count_of(face[0]);
    if (corners < 0)  // CGAL reads the digits before any junk and allocates for them
      throw InputError(path,
                       "face " + std::to_string(f) + ": '" + face[0] + "' is not a corner count");
    if (corners > words_left - 1)
      throw InputError(path, "face " + std::to_string(f) + " declares " + face[0] +
                                 " corners, more than the numbers left in the file");
    // CGAL's reader casts each index to an unsigned type unchecked (UB for -2; fuzz_mesh).
    for (long long k = 1; k <= corners && k < (long long)face.size(); ++k) {
      const long long index = count_of(face[size_t(k)]);
      if (index < 0 || index >= vertices)
        throw InputError(path, "face " + std::to_string(f) + " corner " + std::to_string(k) +
                                   ": '" + face[size_t(k)] + "' is not a vertex index in [0, " +
                                   std::to_string(vertices) + ")");
    }
    words_left -= (long long)face.size();
  }
}

struct PlyProperty {
  bool list = false;
  int count_size = 0, item_size = 0;  // bytes (binary); for scalars item_size only
};
struct PlyElement {
  std::string name;
  long long count = 0;
  std::vector<PlyProperty> properties;
};

int ply_type_size(const std::string& type) {
  static const char* const one[] = {"char", "uchar", "int8", "uint8"};
  static const char* const two[] = {"short", "ushort", "int16", "uint16"};
  static const char* const four[] = {"int", "uint", "int32", "uint32", "float", "float32"};
  for (const char* t : one)
    if (type == t) return 1;
  for (const char* t : two)
    if (type == t) return 2;
  for (const char* t : four)
    if (type == t) return 4;
  if (type == "double" || type == "float64") return 8;
  return 0;
}

uint64_t read_unsigned(const char* p, int size, bool big_endian) {
  uint64_t v = 0;
  for (int i = 0; i < size; ++i)
    v |= uint64_t(uint8_t(p[big_endian ? size - 1 - i : i])) << (8 * i);
  return v;
}

// PLY: the header read by its grammar (any other line is an input error: CGAL's reader reads
// on through unknown lines and sizes lists from garbage, or runs for minutes; found by
// fuzz_mesh), then every element walked through the data: element counts and list lengths may
// not run past the end of the file.
void check_ply(const std::string& path, const std::string& text) {
  std::istringstream in(text);
  std::string line, format;
  std::vector<PlyElement> elements;
  size_t data_start = std::string::npos;
  int number = 0;
  const auto bad_line = [&](const std::string& why) {
    throw InputError(path, "PLY header line " + std::to_string(number) + " '" + line + "': " + why);
  };
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::vector<std::string> w = split_words(line);
    if (number == 1) {
      if (w.size() != 1 || w[0] != "ply") bad_line("a PLY file starts with a line 'ply'");
      continue;
    }
    if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
    if (w[0] == "end_header") {
      data_start = size_t(in.tellg());
      break;
    }
    if (w[0] == "format") {
      if (!format.empty() || !elements.empty()) bad_line("one format line, before the elements");
      if (w.size() != 3 || w[2] != "1.0" ||
          (w[1] != "ascii" && w[1] != "binary_little_endian" && w[1] != "binary_big_endian"))
        bad_line("expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
      format = w[1];
    } else if (w[0] == "element") {
      if (w.size() != 3 || count_of(w[2]) < 0) bad_line("expected 'element NAME COUNT'");
      elements.push_back({w[1], count_of(w[2]), {}});
    } else if (w[0] == "property") {
      // CGAL's reader adds a property to its last element without checking there is one.
      if (elements.empty()) bad_line("a 'property' line comes before any 'element' line");
      PlyProperty p;
      if (w.size() == 5 && w[1] == "list") {
        p.list = true, p.count_size = ply_type_size(w[2]), p.item_size = ply_type_size(w[3]);
      } else if (w.size() == 3) {
        p.item_size = ply_type_size(w[1]);
      } else {
        bad_line("expected 'property TYPE NAME' or 'property list TYPE TYPE NAME'");
      }
      if (p.item_size == 0 || (p.list && p.count_size == 0)) bad_line("unknown property type");
      // CGAL reads a vertex's x, y and z as float or double and, in a release build, follows a
      // failed cast for any other type (a segfault; an assertion in debug builds: fuzz_mesh).
      const std::string& name = w.back();
      const bool coordinate = name == "x" || name == "y" || name == "z";
      const bool floating = !p.list && (w[1] == "float" || w[1] == "float32" || w[1] == "double" ||
                                        w[1] == "float64");
      if ((elements.back().name == "vertex" || elements.back().name == "vertices") && coordinate &&
          !floating)
        bad_line("a vertex coordinate must be a float or double property");
      elements.back().properties.push_back(p);
    } else {
      bad_line("not a PLY header line (format, element, property, comment, end_header)");
    }
  }
  if (number == 0) return;  // empty: CGAL says why
  if (data_start == std::string::npos || data_start > text.size())
    throw InputError(path, "the PLY header has no 'end_header' line");
  if (format.empty()) throw InputError(path, "the PLY header has no 'format' line");
  const auto too_long = [&](const PlyElement& e, long long i, const std::string& what) {
    throw InputError(path, "element '" + e.name + "' " + std::to_string(i) + " of " +
                               std::to_string(e.count) + ": " + what +
                               " runs past the end of the file");
  };
  if (format == "ascii") {
    std::istringstream data(text.substr(data_start));
    std::vector<std::string> words;
    for (std::string w; data >> w;) words.push_back(w);
    size_t at = 0;
    for (const PlyElement& e : elements) {
      if (e.count < 0 || e.properties.empty()) continue;
      for (long long i = 0; i < e.count; ++i)
        for (const PlyProperty& p : e.properties) {
          if (at >= words.size()) too_long(e, i, "its data");
          if (!p.list) {
            ++at;
            continue;
          }
          const long long n = count_of(words[at++]);
          if (n < 0) return;  // not a count: CGAL names the problem
          if (n > (long long)(words.size() - at)) too_long(e, i, "a list of " + std::to_string(n));
          at += size_t(n);
        }
    }
    return;
  }
  const bool big_endian = format == "binary_big_endian";
  size_t at = data_start;
  for (const PlyElement& e : elements) {
    if (e.count < 0 || e.properties.empty()) continue;
    for (long long i = 0; i < e.count; ++i)
      for (const PlyProperty& p : e.properties) {
        if (!p.list) {
          if (p.item_size > (long long)(text.size() - at)) too_long(e, i, "its data");
          at += size_t(p.item_size);
          continue;
        }
        if (p.count_size > (long long)(text.size() - at)) too_long(e, i, "its data");
        const uint64_t n = read_unsigned(text.data() + at, p.count_size, big_endian);
        at += size_t(p.count_size);
        if (n > (text.size() - at) / size_t(p.item_size))
          too_long(e, i, "a list of " + std::to_string(n));
        at += size_t(n) * size_t(p.item_size);
      }
  }
}

}  // namespace

void check_mesh_declared_counts(const std::string& path, const std::string& extension) {
  if (extension == ".off") check_off(path, read_bytes(path));
  if (extension == ".ply") check_ply(path, read_bytes(path));
}

}  // namespace dv
