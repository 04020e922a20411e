// The probe CSV writes every number in the shortest form that reads back as the same double:
// a point given as 0.148 is echoed as 0.148 (not 0.14799999999999999), and values round-trip.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "render/io/points_csv.h"

namespace dv {
namespace {

TEST(PointsCsv, NumbersAreWrittenInTheirShortestRoundTripForm) {
  const std::string path =
      (std::filesystem::temp_directory_path() / "deepvox_points_csv_test.csv").string();
  const std::vector<dvec3> points = {{0.148, -2.5, 1e-30}, {1.0 / 3.0, 100.0, 0.1 + 0.2}};
  const std::vector<double> values = {0.7, 2.0 / 3.0};
  const std::vector<dvec3> rgb = {{0.7, 0.25, 1.0}, {0.5, 0.5, 0.125}};
  write_transmittance_csv(path, points, values, rgb, 1);
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::filesystem::remove(path);
  EXPECT_EQ(text.substr(0, text.find('\n', text.find('\n') + 1) + 1),
            "x,y,z,light0,light0_r,light0_g,light0_b\n0.148,-2.5,1e-30,0.7,0.7,0.25,1\n");
  // Every field of the second row reads back as the double written.
  std::istringstream rows(text);
  std::string row;
  std::getline(rows, row), std::getline(rows, row), std::getline(rows, row);
  const std::vector<double> expected = {1.0 / 3.0, 100.0, 0.1 + 0.2, 2.0 / 3.0, 0.5, 0.5, 0.125};
  std::istringstream fields(row);
  std::string field;
  for (double e : expected) {
    ASSERT_TRUE(std::getline(fields, field, ','));
    EXPECT_EQ(std::strtod(field.c_str(), nullptr), e) << field;
  }
  EXPECT_EQ(row.substr(0, row.find(',')), "0.3333333333333333");
}

}  // namespace
}  // namespace dv
