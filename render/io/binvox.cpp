// binvox writer and reader (format and axis order in binvox.h).
#include "render/io/binvox.h"

#include <algorithm>
#include <bit>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <vector>

#include "core/bits.h"
#include "core/error.h"

namespace dv {

namespace {

// binvox's encoding of the voxel stream: (value, count) byte pairs, count 1..255.
class RunWriter {
 public:
  explicit RunWriter(std::vector<char>& out) : out_(out) {}
  // Appends `count` voxels of `value`.
  void push(bool value, int64_t count) {
    const uint8_t v = value ? 1 : 0;
    if (count_ > 0 && v != value_) flush();
    value_ = v;
    while (count > 0) {
      const int64_t take = std::min<int64_t>(count, 255 - count_);
      count_ += int(take);
      count -= take;
      if (count_ == 255) flush();
    }
  }
  // Appends the first `count` bits of `bits` (low bit of word 0 first).
  void push_bits(const uint32_t* bits, int count) {
    for (int pos = 0; pos < count;) {
      const uint32_t rest = bits[pos / 32] >> (pos % 32);
      const bool value = rest & 1u;
      const int run = std::min(
          {value ? std::countr_one(rest) : std::countr_zero(rest), 32 - pos % 32, count - pos});
      push(value, run);
      pos += run;
    }
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

// Appends one x of the grid, voxels in z, then y order. Word (k, y) of that x is
// slabs[(k * height + y) * stride]: each slab's y column is bit-transposed 32 words at a time
// into one y mask per slice, whose runs are found a word at a time; a slab with no bit at all
// is one run of 32 H empty voxels.
void encode_x(const uint32_t* slabs, size_t stride, int height, int slab_count, RunWriter& out) {
  const int mask_words = (height + 31) / 32;
  std::vector<uint32_t> masks(size_t(32) * mask_words);  // (slice bit, y / 32)
  for (int k = 0; k < slab_count; ++k) {
    const uint32_t* column = slabs + size_t(k) * height * stride;
    uint32_t any = 0;
    for (int m = 0; m < mask_words; ++m) {
      uint32_t t[32];
      for (int i = 0; i < 32; ++i) {
        const int y = m * 32 + i;
        t[i] = y < height ? column[size_t(y) * stride] : 0u;
        any |= t[i];
      }
      transpose_bits32(t);
      for (int bit = 0; bit < 32; ++bit) masks[size_t(bit) * mask_words + m] = t[bit];
    }
    if (!any) {
      out.push(false, int64_t(32) * height);
      continue;
    }
    for (int bit = 0; bit < 32; ++bit) out.push_bits(&masks[size_t(bit) * mask_words], height);
  }
}

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

  // binvox order is x, then z, then y (fastest); the grid's words run x fastest. So the words
  // are read 16 x at a time (a cache line of each row; one x at a time would touch a page per
  // word) into a block in (k, y, x) order, and each x is encoded from it.
  std::vector<uint32_t> device_words;
  if (grid.memory() == Memory::device) device_words = grid.words();
  const uint32_t* words = device_words.empty() ? grid.view().words : device_words.data();
  const int slab_count = r.z / 32;
  const size_t row = size_t(slab_count) * r.y;  // words per x, in (k, y) order
  constexpr int kBlock = 16;
  std::vector<uint32_t> block(row * kBlock);
  std::vector<char> data;
  RunWriter runs(data);
  for (int x0 = 0; x0 < r.x; x0 += kBlock) {
    const int width = std::min(kBlock, r.x - x0);
    for (size_t w = 0; w < row; ++w) std::copy_n(&words[w * r.x + x0], width, &block[w * kBlock]);
    for (int dx = 0; dx < width; ++dx) encode_x(&block[size_t(dx)], kBlock, r.y, slab_count, runs);
  }
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
