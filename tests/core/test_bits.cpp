// The bit helpers of core/bits.h against plain per-bit loops: counting, masking, float patterns
// and the 32 x 32 transpose that binvox writing relies on.
#include <gtest/gtest.h>

#include <cstdint>
#include <iterator>
#include <random>

#include "core/bits.h"

namespace dv {
namespace {

TEST(Bits, TransposeMovesBitJOfWordIToBitIOfWordJ) {
  std::mt19937 random(7);
  for (int trial = 0; trial < 20; ++trial) {
    uint32_t in[32], out[32];
    for (int i = 0; i < 32; ++i) out[i] = in[i] = random() & (trial % 2 ? 0xffffffffu : random());
    transpose_bits32(out);
    for (int i = 0; i < 32; ++i)
      for (int j = 0; j < 32; ++j)
        ASSERT_EQ((out[i] >> j) & 1u, (in[j] >> i) & 1u) << "word " << i << " bit " << j;
    transpose_bits32(out);
    for (int i = 0; i < 32; ++i) EXPECT_EQ(out[i], in[i]) << "twice is the identity, word " << i;
  }
}

TEST(Bits, FloatPatternsRoundTripAndOrderLikeNonNegativeValues) {
  const float values[] = {0.0f, 1e-30f, 0.02f, 0.5f, 1.0f, 3.5f, 1e30f};
  for (size_t i = 0; i < std::size(values); ++i) {
    EXPECT_EQ(bits_float(float_bits(values[i])), values[i]);
    if (i > 0) EXPECT_LT(float_bits(values[i - 1]), float_bits(values[i])) << values[i];
  }
}

TEST(Bits, CountAndBelow) {
  EXPECT_EQ(bit_count(0u), 0);
  EXPECT_EQ(bit_count(0xffffffffu), 32);
  EXPECT_EQ(bit_count(0x80000001u), 2);
  EXPECT_EQ(bits_below(0xffffffffu, 0), 0u);
  EXPECT_EQ(bits_below(0xffffffffu, 5), 0x1fu);
  EXPECT_EQ(bits_below(0xdeadbeefu, 32), 0xdeadbeefu);
}

}  // namespace
}  // namespace dv
