// Tests of the smoke plume (determinism per seed, variety across seeds, zero border, a dense
// core that widens with height) and of the constant block.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "render/load/volume_generators.h"

namespace dv {
namespace {

float at(const VolumeGrid& v, int i, int j, int k) {
  return v.density[size_t((int64_t(k) * v.dims.y + j) * v.dims.x + i)];
}

bool on_border(const VolumeGrid& v, int i, int j, int k) {
  return i == 0 || j == 0 || k == 0 || i == v.dims.x - 1 || j == v.dims.y - 1 || k == v.dims.z - 1;
}

int nonzero_in_row_slab(const VolumeGrid& v, int j) {
  int count = 0;
  for (int k = 0; k < v.dims.z; ++k)
    for (int i = 0; i < v.dims.x; ++i) count += at(v, i, j, k) > 0.0f;
  return count;
}

const ivec3 kSmokeDims(40, 56, 36);

TEST(Smoke, SameSeedIsBitIdentical) {
  const VolumeGrid a = make_smoke_plume(kSmokeDims, 42);
  const VolumeGrid b = make_smoke_plume(kSmokeDims, 42);
  ASSERT_EQ(a.density.size(), size_t(kSmokeDims.x) * kSmokeDims.y * kSmokeDims.z);
  ASSERT_EQ(a.density.size(), b.density.size());
  EXPECT_TRUE(std::equal(a.density.begin(), a.density.end(), b.density.begin()));
  EXPECT_EQ(a.origin, dvec3(-1.0));
}

TEST(Smoke, DifferentSeedsDiffer) {
  const VolumeGrid a = make_smoke_plume(kSmokeDims, 1);
  const VolumeGrid b = make_smoke_plume(kSmokeDims, 2);
  size_t differing = 0, occupied = 0;
  for (size_t i = 0; i < a.density.size(); ++i) {
    differing += a.density[i] != b.density[i];
    occupied += a.density[i] > 0.0f || b.density[i] > 0.0f;
  }
  EXPECT_GT(occupied, size_t(1000));
  EXPECT_GT(differing, occupied / 2);
}

TEST(Smoke, DensitiesInRangeZeroBorderDenseCore) {
  for (uint64_t seed : {1ull, 7ull, 123456789ull}) {
    const VolumeGrid v = make_smoke_plume(kSmokeDims, seed, 1.0);
    float max_inside = 0.0f;
    int border_nonzero = 0, out_of_range = 0;
    for (int k = 0; k < v.dims.z; ++k)
      for (int j = 0; j < v.dims.y; ++j)
        for (int i = 0; i < v.dims.x; ++i) {
          const float d = at(v, i, j, k);
          out_of_range += !(d >= 0.0f && d <= 1.0f);
          if (on_border(v, i, j, k)) {
            border_nonzero += d != 0.0f;
          } else {
            max_inside = std::max(max_inside, d);
          }
        }
    EXPECT_EQ(out_of_range, 0) << "seed " << seed;
    EXPECT_EQ(border_nonzero, 0) << "seed " << seed;
    EXPECT_GT(max_inside, 0.3f) << "seed " << seed;
  }
}

TEST(Smoke, SmoothColumnWidensWithHeight) {
  // Without turbulence the plume is a column of revolution about the y axis: the seed has no
  // effect, and higher rows hold more occupied samples than lower ones.
  const ivec3 dims(33, 33, 33);  // spacing 1/16: mirrored samples have exactly negated coordinates
  const VolumeGrid calm = make_smoke_plume(dims, 5, 0.0);
  const VolumeGrid other_seed = make_smoke_plume(dims, 6, 0.0);
  EXPECT_TRUE(std::equal(calm.density.begin(), calm.density.end(), other_seed.density.begin()));
  const int low = nonzero_in_row_slab(calm, 8);    // t = 0.25
  const int high = nonzero_in_row_slab(calm, 22);  // t = 0.69
  EXPECT_GT(low, 0);
  EXPECT_GT(high, 2 * low);
  EXPECT_GT(at(calm, 16, 8, 16), 0.3f);                   // on the axis
  EXPECT_EQ(at(calm, 16, 8, 16 + 7), 0.0f);               // outside the narrow lower column
  EXPECT_GT(at(calm, 16, 22, 16 + 4), 0.0f);              // inside the wider upper column
  EXPECT_EQ(at(calm, 12, 16, 16), at(calm, 20, 16, 16));  // mirror symmetric
  EXPECT_EQ(at(calm, 16, 16, 11), at(calm, 11, 16, 16));  // rotationally symmetric (90 deg)
}

TEST(Smoke, TinyGridsAreAllBorder) {
  const VolumeGrid v = make_smoke_plume({2, 3, 2}, 1);
  ASSERT_EQ(v.density.size(), size_t(12));
  EXPECT_TRUE(std::all_of(v.density.begin(), v.density.end(), [](float d) { return d == 0.0f; }));
}

TEST(Smoke, RejectsBadParameters) {
  EXPECT_THROW(make_smoke_plume({8, 8, 8}, 1, -0.5), InputError);
  EXPECT_THROW(make_smoke_plume({8, 8, 8}, 1, std::nan("")), InputError);
  EXPECT_THROW(make_smoke_plume({8, 0, 8}, 1), InputError);
}

TEST(Block, EverySampleHoldsTheDensity) {
  const VolumeGrid v = make_constant_block({3, 4, 5}, 0.4f);
  ASSERT_EQ(v.density.size(), size_t(60));
  EXPECT_TRUE(std::all_of(v.density.begin(), v.density.end(), [](float d) { return d == 0.4f; }));
  EXPECT_EQ(v.origin, dvec3(-1.0));
  EXPECT_DOUBLE_EQ(v.spacing.y, 2.0 / 3.0);
  EXPECT_THROW(make_constant_block({3, 4, 5}, 1.5f), InputError);
  EXPECT_THROW(make_constant_block({3, 4, 5}, -0.1f), InputError);
  EXPECT_THROW(make_constant_block({0, 4, 5}, 0.5f), InputError);
}

}  // namespace
}  // namespace dv
