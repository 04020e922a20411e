// Text helpers: the edit distance and the nearest-word suggestion the CLI's "did you mean" uses,
// and numbers as text (core/number_text.h): significant digits, signs, whole numbers in tables,
// and the shortest text that reads back as the same double or float.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "core/number_text.h"
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

TEST(NumberText, SignificantDigits) {
  EXPECT_EQ(significant_text(0.0123456, 3), "0.0123");
  EXPECT_EQ(significant_text(1234567.0, 3), "1.23e+06");
  EXPECT_EQ(significant_text(2.5, 4), "2.5");
  EXPECT_EQ(signed_text(0.5, 3), "+0.5");
  EXPECT_EQ(signed_text(0.0, 3), "+0");
  EXPECT_EQ(signed_text(-0.25, 3), "-0.25");
}

TEST(NumberText, TablesPrintWholeNumbersInFull) {
  EXPECT_EQ(table_text(1048576.0, 4), "1048576");
  EXPECT_EQ(table_text(-3.0, 4), "-3");
  EXPECT_EQ(table_text(0.123456, 4), "0.1235");
  EXPECT_EQ(table_text(1e20, 4), "1e+20");
}

TEST(NumberText, ExactTextReadsBackAsTheSameValue) {
  EXPECT_EQ(exact_text(0.1), "0.1");
  EXPECT_EQ(exact_text(1234567.0), "1234567");
  EXPECT_EQ(exact_text(0.1 + 0.2), "0.30000000000000004");
  EXPECT_EQ(exact_text(0.01f), "0.01");
  for (double v : {1.0 / 3.0, 6.02214076e23, -2.5e-310, 123.456789012345})
    EXPECT_EQ(std::strtod(exact_text(v).c_str(), nullptr), v) << exact_text(v);
  for (float v : {1.0f / 3.0f, 3.4e38f, 1e-45f})
    EXPECT_EQ(std::strtof(exact_text(v).c_str(), nullptr), v) << exact_text(v);
}

}  // namespace
}  // namespace dv
