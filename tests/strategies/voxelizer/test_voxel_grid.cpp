// The voxel grid (bit layout, limits, set/get/popcount), its MIP levels on odd sizes, and
// binvox files (round trip, axis order, malformed input).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>

#include "core/error.h"
#include "render/io/binvox.h"
#include "tests/strategies/voxelizer/voxel_test_support.h"

namespace dv {
namespace {

std::string scratch_file(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / "deepvox_test_voxel";
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

TEST(VoxelGrid, BitLayoutAndCounts) {
  VoxelGrid grid(test::unit_grid({5, 3, 64}), Memory::host);
  EXPECT_EQ(grid.spec().word_count(), 5 * 3 * 2);
  grid.set(4, 2, 63);
  grid.set(0, 0, 0);
  grid.set(1, 2, 33);
  grid.set(1, 2, 33);  // setting twice keeps one voxel
  EXPECT_EQ(grid.popcount(), 3);
  EXPECT_TRUE(grid.get(4, 2, 63));
  EXPECT_TRUE(grid.get(1, 2, 33));
  EXPECT_FALSE(grid.get(1, 2, 32));
  const std::vector<uint32_t> words = grid.words();
  EXPECT_EQ(words[size_t((1 * 3 + 2) * 5 + 4)], 1u << 31);  // word (4, 2, k=1), bit 31
  EXPECT_EQ(words[size_t((1 * 3 + 2) * 5 + 1)], 1u << 1);   // word (1, 2, k=1), bit 1
  EXPECT_EQ(words[0], 1u);
  grid.clear();
  EXPECT_EQ(grid.popcount(), 0);
  EXPECT_THROW(grid.get(5, 0, 0), Error);
  EXPECT_THROW(grid.set(0, 0, 64), Error);
}

TEST(VoxelGrid, SpecLimitsAreInputErrors) {
  const Aabb box{dvec3(0.0), dvec3(1.0)};
  EXPECT_NO_THROW(make_box_grid({1024, 1024, 1024}, box));
  EXPECT_THROW(make_box_grid({8, 8, 40}, box), InputError);  // depth not a multiple of 32
  EXPECT_THROW(make_box_grid({0, 8, 32}, box), InputError);
  EXPECT_THROW(make_box_grid({8, 8, 8192}, box), InputError);
  EXPECT_THROW(make_box_grid({16384, 16384, 4096}, box), InputError);  // too many voxels
  EXPECT_THROW(make_box_grid({8, 8, 32}, Aabb{dvec3(0.0), dvec3(1.0, 0.0, 1.0)}), InputError);
  try {
    make_box_grid({8, 8, 31}, box, "--res");
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--res"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("multiple of 32"), std::string::npos);
  }
}

TEST(VoxelGrid, TransformPutsTheUpperFaceInTheLastVoxel) {
  const GridSpec spec = make_box_grid({4, 2, 32}, Aabb{dvec3(-1.0), dvec3(1.0, 3.0, 7.0)});
  const GridTransform t = grid_transform(spec);
  EXPECT_EQ(t.apply(dvec3(-1.0)), dvec3(0.0));
  EXPECT_EQ(t.apply(dvec3(1.0, 3.0, 7.0)), dvec3(4.0, 2.0, 32.0));
  EXPECT_EQ(spec.voxel_size(), dvec3(0.5, 2.0, 0.25));
}

TEST(VoxelGrid, MipLevelsOrTwoByTwoAndKeepOddEdges) {
  VoxelGrid grid(test::unit_grid({7, 5, 64}), Memory::host);
  grid.set(6, 4, 40);  // last column and last row of an odd-sized level
  grid.set(2, 1, 3);
  grid.set(3, 0, 3);
  grid.set(0, 0, 63);
  const std::vector<VoxelGrid> chain = mip_chain(grid);
  ASSERT_EQ(chain.size(), 3u);  // 4x3, 2x2, 1x1
  EXPECT_EQ(chain[0].spec().res, ivec3(4, 3, 64));
  EXPECT_EQ(chain[1].spec().res, ivec3(2, 2, 64));
  EXPECT_EQ(chain[2].spec().res, ivec3(1, 1, 64));
  const VoxelGrid& l1 = chain[0];
  EXPECT_TRUE(l1.get(3, 2, 40));
  EXPECT_TRUE(l1.get(1, 0, 3));  // (2,1) and (3,0) both land in texel (1,0)
  EXPECT_TRUE(l1.get(0, 0, 63));
  EXPECT_EQ(l1.popcount(), 3);
  EXPECT_TRUE(chain[1].get(1, 1, 40));
  EXPECT_TRUE(chain[1].get(0, 0, 3));
  EXPECT_TRUE(chain[1].get(0, 0, 63));
  EXPECT_EQ(chain[2].popcount(), 3);
  EXPECT_TRUE(chain[2].get(0, 0, 40) && chain[2].get(0, 0, 3) && chain[2].get(0, 0, 63));
  // Voxels exactly twice as wide: the odd level's box grows by half a coarse voxel.
  EXPECT_EQ(l1.spec().voxel_size(), dvec3(2.0, 2.0, 1.0));
  EXPECT_EQ(l1.spec().bounds.hi, dvec3(8.0, 6.0, 64.0));
}

TEST(VoxelGrid, MipMatchesABruteForceOr) {
  std::mt19937 rng(7);
  VoxelGrid grid(test::unit_grid({13, 9, 32}), Memory::host);
  for (int i = 0; i < 200; ++i) grid.set(int(rng() % 13), int(rng() % 9), int(rng() % 32));
  const VoxelGrid level = mip_down(grid);
  for (int z = 0; z < 32; ++z)
    for (int y = 0; y < 5; ++y)
      for (int x = 0; x < 7; ++x) {
        bool any = false;
        for (int sy = 2 * y; sy < std::min(2 * y + 2, 9); ++sy)
          for (int sx = 2 * x; sx < std::min(2 * x + 2, 13); ++sx) any = any || grid.get(sx, sy, z);
        EXPECT_EQ(level.get(x, y, z), any) << x << " " << y << " " << z;
      }
}

TEST(Binvox, RoundTripKeepsEveryVoxelAndTheBox) {
  const GridSpec spec =
      make_box_grid({12, 20, 32}, Aabb{dvec3(-1.0, 2.0, 0.5), dvec3(0.2, 4.0, 3.7)});
  VoxelGrid grid(spec, Memory::host);
  std::mt19937 rng(11);
  for (int i = 0; i < 900; ++i) grid.set(int(rng() % 12), int(rng() % 20), int(rng() % 32));
  for (int y = 0; y < 20; ++y) grid.set(3, y, 5);  // a run longer than nothing in particular
  const std::string path = scratch_file("round_trip.binvox");
  write_binvox(path, grid);
  const BinvoxFile file = read_binvox(path);
  EXPECT_EQ(file.grid.spec().res, spec.res);
  EXPECT_EQ(file.grid.words(), grid.words());
  EXPECT_EQ(file.translate, spec.bounds.lo);
  EXPECT_NEAR(file.scale, 32 * 0.1, 1e-12);  // voxel width in x times the largest dim
  EXPECT_NEAR(file.grid.spec().bounds.lo.x, -1.0, 1e-12);
  EXPECT_NEAR(file.grid.spec().bounds.hi.x, 0.2, 1e-12);
}

TEST(Binvox, HeaderAndRunOrderFollowTheFormat) {
  VoxelGrid grid(test::unit_grid({2, 3, 32}), Memory::host);
  grid.set(1, 2, 0);  // index x*(Z*Y) + z*Y + y = 96 + 0 + 2 = 98 of 192
  for (int z = 0; z < 32; ++z) grid.set(0, 0, z);  // indices 0, 3, 6, ... (y innermost)
  const std::string path = scratch_file("order.binvox");
  write_binvox(path, grid);
  std::ifstream in(path, std::ios::binary);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "#binvox 1");
  std::getline(in, line);
  EXPECT_EQ(line, "dim 2 32 3");  // x count, z count, y count
  std::getline(in, line);
  EXPECT_EQ(line.rfind("translate 0 0 0", 0), 0u);
  std::getline(in, line);
  EXPECT_EQ(line, "scale 32");
  std::getline(in, line);
  EXPECT_EQ(line, "data");
  std::vector<int> stream;
  char pair[2];
  while (in.read(pair, 2))
    for (int i = 0; i < uint8_t(pair[1]); ++i) stream.push_back(pair[0]);
  ASSERT_EQ(stream.size(), 192u);
  for (int i = 0; i < 192; ++i) {
    const bool expected = i == 98 || (i < 96 && i % 3 == 0);
    EXPECT_EQ(stream[size_t(i)], expected ? 1 : 0) << i;
  }
}

TEST(Binvox, LongRunsSplitAt255) {
  VoxelGrid grid(test::unit_grid({16, 16, 32}), Memory::host);
  for (int x = 0; x < 16; ++x)
    for (int y = 0; y < 16; ++y)
      for (int z = 0; z < 32; ++z) grid.set(x, y, z);
  const std::string path = scratch_file("full.binvox");
  write_binvox(path, grid);
  EXPECT_EQ(read_binvox(path).grid.popcount(), 16 * 16 * 32);
}

// The writer works a word slab at a time (bit transposes, whole-word runs); its bytes must be
// those of the format's definition: every voxel in x, z, y order, runs cut at 255. Sizes off
// its 16-wide blocks and 32-row transposes, empty and full slabs, long and short runs.
TEST(Binvox, WriterBytesMatchTheVoxelByVoxelEncoding) {
  for (const ivec3 res : {ivec3{37, 45, 96}, ivec3{16, 32, 32}, ivec3{1, 300, 64}}) {
    VoxelGrid grid(test::unit_grid(res), Memory::host);
    std::mt19937 rng(uint32_t(res.x * 7 + res.y));
    for (int i = 0; i < res.x * res.y; ++i)
      grid.set(int(rng() % res.x), int(rng() % res.y), int(rng() % res.z));
    for (int x = 0; x < res.x; x += 3)  // full slices and a full slab
      for (int y = 0; y < res.y; ++y) {
        grid.set(x, y, res.z - 1);
        for (int z = 0; z < 32; ++z)
          if (x % 2 == 0) grid.set(x, y, z);
      }
    std::string expected;
    int value = -1, count = 0;
    auto flush = [&] {
      if (count) expected += {char(value), char(count)};
      count = 0;
    };
    for (int x = 0; x < res.x; ++x)
      for (int z = 0; z < res.z; ++z)
        for (int y = 0; y < res.y; ++y) {
          const int v = grid.get(x, y, z) ? 1 : 0;
          if (count && (v != value || count == 255)) flush();
          value = v;
          ++count;
        }
    flush();
    const std::string path = scratch_file("bytes.binvox");
    write_binvox(path, grid);
    std::ifstream in(path, std::ios::binary);
    std::string line;
    for (int i = 0; i < 5; ++i) std::getline(in, line);  // the header's five lines
    ASSERT_EQ(line, "data");
    const std::string data{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    EXPECT_EQ(data.size(), expected.size()) << res.x << "x" << res.y << "x" << res.z;
    EXPECT_TRUE(data == expected) << res.x << "x" << res.y << "x" << res.z;
  }
}

TEST(Binvox, MalformedFilesAreInputErrorsNamingTheFile) {
  const auto write = [](const std::string& name, const std::string& bytes) {
    const std::string path = scratch_file(name);
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
  };
  const std::string header = "#binvox 1\ndim 1 32 1\ntranslate 0 0 0\nscale 1\ndata\n";
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"version.binvox", "#binvox 3\ndim 1 32 1\ndata\n"},
      {"nodim.binvox", "#binvox 1\ndata\n"},
      {"depth.binvox", "#binvox 1\ndim 1 30 1\ndata\n"},
      {"short.binvox", header + std::string("\x01\x10", 2)},
      {"long.binvox", header + std::string("\x01\x20\x00\x01", 4)},
      {"value.binvox", header + std::string("\x02\x20", 2)},
      {"zero.binvox", header + std::string("\x01\x00\x01\x20", 4)},
      {"half.binvox", header + std::string("\x01\x20\x01", 3)},
      {"header.binvox", "#binvox 1\ndim 1 32\ndata\n"},
  };
  for (const auto& [name, bytes] : bad) {
    const std::string path = write(name, bytes);
    try {
      read_binvox(path);
      ADD_FAILURE() << name << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(read_binvox(scratch_file("does_not_exist.binvox")), InputError);
  const std::string ok = write("ok.binvox", header + std::string("\x00\x1f\x01\x01", 4));
  const BinvoxFile file = read_binvox(ok);
  EXPECT_EQ(file.grid.popcount(), 1);
  EXPECT_TRUE(file.grid.get(0, 0, 31));
}

}  // namespace
}  // namespace dv
