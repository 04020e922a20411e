// binvox writer and reader (format and axis order in binvox.h).
#include "io/binvox.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <vector>

#include "core/error.h"

namespace dv {

namespace {

// Run-length encoder over the voxel stream.
class RunWriter {
 public:
  explicit RunWriter(std::vector<char>& out) : out_(out) {}
  void push(bool value) {
    const uint8_t v = value ? 1 : 0;
    if (count_ > 0 && (v != value_ || count_ == 255)) flush();
    value_ = v;
    ++count_;
  }
  void flush() {
    if (count_ == 0) return;
    out_.push_back(char(value_));
    out_.push_back(char(uint8_t(count_)));
    count_ = 0;
  }

 private:
  std::vector<char>& out_;
  uint8_t value_ = 0;
  int count_ = 0;
};

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

}  // namespace

void write_binvox(const std::string& path, const VoxelGrid& grid) {
  const GridSpec& spec = grid.spec();
  const ivec3 r = spec.res;
  const int max_dim = std::max({r.x, r.y, r.z});
  const double scale = spec.voxel_size().x * max_dim;
  std::ostringstream header;
  header << "#binvox 1\n"
         << "dim " << r.x << " " << r.z << " " << r.y << "\n"
         << "translate " << number(spec.bounds.lo.x) << " " << number(spec.bounds.lo.y) << " "
         << number(spec.bounds.lo.z) << "\n"
         << "scale " << number(scale) << "\n"
         << "data\n";

  const std::vector<uint32_t> words = grid.words();
  const VoxelGridView view{const_cast<uint32_t*>(words.data()), r.x, r.y, r.z};
  std::vector<char> data;
  RunWriter runs(data);
  for (int x = 0; x < r.x; ++x)
    for (int z = 0; z < r.z; ++z)
      for (int y = 0; y < r.y; ++y) runs.push(view.get(x, y, z));
  runs.flush();

  std::ofstream out(path, std::ios::binary);
  if (!out) throw InputError(path, "cannot write binvox file");
  const std::string h = header.str();
  out.write(h.data(), std::streamsize(h.size()));
  out.write(data.data(), std::streamsize(data.size()));
  if (!out) throw InputError(path, "writing the binvox file failed");
}

BinvoxFile read_binvox(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "cannot open binvox file");
  auto next_line = [&](const char* expected) {
    std::string line;
    if (!std::getline(in, line))
      throw InputError(path, std::string("binvox header ends before ") + expected);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    return line;
  };
  if (next_line("the version line") != "#binvox 1")
    throw InputError(path, "not a version-1 binvox file (first line must be '#binvox 1')");

  BinvoxFile file;
  long long dims[3] = {0, 0, 0};  // X Z Y as in the file
  bool have_dim = false;
  for (;;) {
    const std::string line = next_line("'data'");
    if (line == "data") break;
    std::istringstream fields(line);
    std::string key;
    fields >> key;
    bool ok = true;
    if (key == "dim") {
      ok = bool(fields >> dims[0] >> dims[1] >> dims[2]);
      have_dim = true;
    } else if (key == "translate") {
      ok = bool(fields >> file.translate.x >> file.translate.y >> file.translate.z);
    } else if (key == "scale") {
      ok = bool(fields >> file.scale);
    } else {
      throw InputError(path, "unknown binvox header line '" + line + "'");
    }
    std::string rest;
    if (!ok || (fields >> rest))
      throw InputError(path, "malformed binvox header line '" + line + "'");
  }
  if (!have_dim) throw InputError(path, "binvox header has no 'dim' line");
  for (long long d : dims)
    if (d <= 0 || d > kMaxGridSide)
      throw InputError(path, "binvox dims must be between 1 and " + std::to_string(kMaxGridSide));
  const ivec3 res{int(dims[0]), int(dims[2]), int(dims[1])};
  if (res.z % 32 != 0)
    throw InputError(path, "binvox z size " + std::to_string(res.z) +
                               " is not a multiple of 32 (the voxel grid packs 32 slices a word)");
  // Each run of two bytes holds at most 255 voxels: a header declaring more voxels than the
  // data can hold is rejected before the grid (up to 2 GiB) is allocated.
  const int64_t total = int64_t(res.x) * res.y * res.z;
  const std::streamoff data_start = in.tellg();
  in.seekg(0, std::ios::end);
  const int64_t data_bytes = int64_t(in.tellg() - data_start);
  in.seekg(data_start);
  if (data_bytes / 2 < (total + 254) / 255)
    throw InputError(path, "binvox dims declare " + std::to_string(total) + " voxels, but " +
                               std::to_string(data_bytes) + " bytes of runs hold at most " +
                               std::to_string(data_bytes / 2 * 255));
  const double unit = file.scale / std::max({res.x, res.y, res.z});
  Aabb bounds;
  bounds.lo = file.translate;
  bounds.hi = file.translate + dvec3(res) * unit;
  file.grid = VoxelGrid(make_box_grid(res, bounds, path), Memory::host);

  const VoxelGridView view = file.grid.view();
  int64_t index = 0;
  char pair[2];
  while (in.read(pair, 2)) {
    const uint8_t value = uint8_t(pair[0]), count = uint8_t(pair[1]);
    if (value > 1) throw InputError(path, "binvox value byte other than 0 or 1");
    if (count == 0) throw InputError(path, "binvox run of length 0");
    if (index + count > total) throw InputError(path, "binvox data holds more voxels than dim");
    if (value)
      for (int64_t i = index; i < index + count; ++i) {
        const int x = int(i / (int64_t(res.z) * res.y));
        const int z = int((i / res.y) % res.z);
        const int y = int(i % res.y);
        view.set(x, y, z);
      }
    index += count;
  }
  if (in.gcount() != 0) throw InputError(path, "binvox data ends in half a run");
  if (index != total)
    throw InputError(path, "binvox data holds " + std::to_string(index) + " voxels, dim says " +
                               std::to_string(total));
  return file;
}

}  // namespace dv
