// Text helpers: the edit distance and the nearest-word suggestion the CLI's "did you mean" uses.
#include <gtest/gtest.h>

#include "core/text.h"

namespace dv {
namespace {

TEST(Text, EditDistance) {
  EXPECT_EQ(edit_distance("render", "render"), 0);
  EXPECT_EQ(edit_distance("renderr", "render"), 1);
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3);
  EXPECT_EQ(edit_distance("", "dsm"), 3);
}

TEST(Text, NearestWordSuggestsOnlyCloseOnes) {
  const std::vector<std::string> commands = {"probe", "render", "info", "list", "voxelize", "dsm"};
  EXPECT_EQ(nearest_word("renderr", commands), "render");
  EXPECT_EQ(nearest_word("voxelise", commands), "voxelize");
  EXPECT_EQ(nearest_word("dms", commands), "dsm");
  EXPECT_EQ(nearest_word("--shadow", {"--out", "--shadows", "--stats"}), "--shadows");
  EXPECT_EQ(nearest_word("completely", commands), "");
}

}  // namespace
}  // namespace dv
