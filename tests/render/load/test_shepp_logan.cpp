// Tests of the 3D Shepp-Logan phantom: known values of the ellipsoid table, agreement of the
// sampled grid with the analytic density, placement on [-1, 1]^3 for cubic, paper-sized and odd
// grids, and mirror symmetry where only the symmetric skull ellipsoids reach.
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

TEST(SheppLogan, AnalyticValuesFollowTheTable) {
  EXPECT_DOUBLE_EQ(shepp_logan_density({0.0, 0.0, 0.0}), 0.2);      // brain tissue
  EXPECT_DOUBLE_EQ(shepp_logan_density({0.0, 0.89, 0.0}), 1.0);     // skull shell (top)
  EXPECT_DOUBLE_EQ(shepp_logan_density({0.0, -0.90, 0.0}), 1.0);    // skull shell (bottom)
  EXPECT_DOUBLE_EQ(shepp_logan_density({0.68, 0.0, 0.0}), 1.0);     // skull shell (side)
  EXPECT_NEAR(shepp_logan_density({0.22, 0.0, 0.0}), 0.0, 1e-12);   // ventricle
  EXPECT_NEAR(shepp_logan_density({-0.22, 0.0, 0.0}), 0.0, 1e-12);  // ventricle
  EXPECT_DOUBLE_EQ(shepp_logan_density({0.0, 0.35, -0.15}), 0.3);   // ellipsoid 5
  EXPECT_DOUBLE_EQ(shepp_logan_density({0.0, 0.1, 0.25}), 0.3);     // ellipsoid 6
  EXPECT_DOUBLE_EQ(shepp_logan_density({0.0, -0.606, 0.0}), 0.3);   // ellipsoid 9
  EXPECT_EQ(shepp_logan_density({0.75, 0.0, 0.0}), 0.0);            // outside the skull
  EXPECT_EQ(shepp_logan_density({0.0, 0.0, 0.85}), 0.0);
  EXPECT_EQ(shepp_logan_density({-1.0, -1.0, -1.0}), 0.0);
  // The ventricle at +x is rotated by -18 degrees: along its tilted long axis it still holds
  // 0, while the mirrored point lies outside it (brain tissue).
  const double c = std::cos(-18.0 * M_PI / 180.0), s = std::sin(-18.0 * M_PI / 180.0);
  const dvec3 along_axis(0.22 - 0.2 * s, 0.2 * c, 0.0);
  EXPECT_NEAR(shepp_logan_density(along_axis), 0.0, 1e-12);
  EXPECT_DOUBLE_EQ(shepp_logan_density({0.22 + 0.2 * s, 0.2 * c, 0.0}), 0.2);
}

TEST(SheppLogan, GridMatchesAnalyticDensityAndPlacement) {
  const ivec3 dims(33, 31, 17);
  const VolumeGrid v = make_shepp_logan_3d(dims);
  ASSERT_EQ(v.dims, dims);
  ASSERT_EQ(v.density.size(), size_t(33 * 31 * 17));
  EXPECT_EQ(v.origin, dvec3(-1.0));
  EXPECT_DOUBLE_EQ(v.spacing.x, 2.0 / 32.0);
  EXPECT_DOUBLE_EQ(v.spacing.y, 2.0 / 30.0);
  EXPECT_DOUBLE_EQ(v.spacing.z, 2.0 / 16.0);
  EXPECT_NEAR(v.bounds().hi.x, 1.0, 1e-12);
  EXPECT_NEAR(v.bounds().hi.z, 1.0, 1e-12);
  int mismatches = 0;
  for (int k = 0; k < dims.z; ++k)
    for (int j = 0; j < dims.y; ++j)
      for (int i = 0; i < dims.x; ++i) {
        const dvec3 p = v.origin + dvec3(i, j, k) * v.spacing;
        if (at(v, i, j, k) != float(shepp_logan_density(p))) ++mismatches;
      }
  EXPECT_EQ(mismatches, 0);
}

TEST(SheppLogan, KnownSamplesOnACubicGrid) {
  const VolumeGrid v = make_shepp_logan_3d({65, 65, 65});  // spacing 1/32: exact coordinates
  EXPECT_FLOAT_EQ(at(v, 32, 32, 32), 0.2f);                // centre of the outer ellipsoid
  EXPECT_EQ(at(v, 0, 0, 0), 0.0f);
  EXPECT_EQ(at(v, 64, 32, 32), 0.0f);
  EXPECT_EQ(at(v, 32, 60, 32), 1.0f);  // y = 0.875: in the skull shell
  EXPECT_EQ(at(v, 32, 3, 32), 1.0f);   // y = -0.906
  const auto [lo, hi] = std::minmax_element(v.density.begin(), v.density.end());
  EXPECT_EQ(*lo, 0.0f);
  EXPECT_EQ(*hi, 1.0f);  // the shell holds the top value
  int tissue = 0;
  for (float d : v.density) tissue += (std::abs(d - 0.2f) < 1e-6f);
  EXPECT_GT(tissue, 65 * 65 * 65 / 10);
}

TEST(SheppLogan, SymmetricWhereOnlyTheSkullEllipsoidsReach) {
  // Away from the ventricles and small features (|x| >= 0.5 or |y| >= 0.75) only ellipsoids
  // 1 and 2 matter, and both are symmetric under x -> -x and z -> -z.
  const int n = 65;
  const VolumeGrid v = make_shepp_logan_3d({n, n, n});
  int compared = 0, shell = 0, asymmetric = 0;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const dvec3 p = v.origin + dvec3(i, j, k) * v.spacing;
        if (std::abs(p.x) < 0.5 && std::abs(p.y) < 0.75) continue;
        ++compared;
        shell += at(v, i, j, k) == 1.0f;
        asymmetric += at(v, i, j, k) != at(v, n - 1 - i, j, k);
        asymmetric += at(v, i, j, k) != at(v, i, j, n - 1 - k);
      }
  EXPECT_GT(compared, 1000);
  EXPECT_GT(shell, 100);
  EXPECT_EQ(asymmetric, 0);
  // The whole phantom is not symmetric in y (ellipsoid 2 sits lower), so the shell is thicker
  // at the top: more shell samples above y = 0.75 than below -0.75.
  int top = 0, bottom = 0;
  for (int k = 0; k < n; ++k)
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const double y = v.origin.y + j * v.spacing.y;
        if (at(v, i, j, k) != 1.0f) continue;
        top += y > 0.75;
        bottom += y < -0.75;
      }
  EXPECT_GT(top, bottom);
}

TEST(SheppLogan, PaperSizedAndOddGrids) {
  const VolumeGrid paper = make_shepp_logan_3d({128, 128, 24});
  ASSERT_EQ(paper.density.size(), size_t(128 * 128 * 24));
  EXPECT_DOUBLE_EQ(paper.spacing.z, 2.0 / 23.0);
  EXPECT_TRUE(std::all_of(paper.density.begin(), paper.density.end(),
                          [](float d) { return d >= 0.0f && d <= 1.0f; }));
  EXPECT_EQ(*std::max_element(paper.density.begin(), paper.density.end()), 1.0f);

  const VolumeGrid odd = make_shepp_logan_3d({7, 5, 3});
  ASSERT_EQ(odd.density.size(), size_t(105));
  EXPECT_FLOAT_EQ(at(odd, 3, 2, 1), 0.2f);  // exact centre
  EXPECT_EQ(at(odd, 0, 2, 1), 0.0f);        // x = -1
  EXPECT_EQ(at(odd, 3, 2, 0), 0.0f);        // z = -1

  const VolumeGrid single = make_shepp_logan_3d({1, 1, 1});
  ASSERT_EQ(single.density.size(), size_t(1));
  EXPECT_FLOAT_EQ(single.density[0], 0.2f);
  EXPECT_EQ(single.origin, dvec3(0.0));
}

TEST(SheppLogan, RejectsEmptyDims) {
  EXPECT_THROW(make_shepp_logan_3d({0, 4, 4}), InputError);
  EXPECT_THROW(make_shepp_logan_3d({4, -1, 4}), InputError);
  try {
    make_shepp_logan_3d({4, 4, 0});
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("zero-size volume"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace dv
