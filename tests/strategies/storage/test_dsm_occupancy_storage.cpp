// The `occupancy` storage (occupancy maps after Sintorn & Assarsson 2009) against closed forms:
// a constant-extinction slab becomes a staircase of one slice's optical depth, surfaces in
// slices of their own are exact, surfaces sharing a slab share its optical depth equally over
// their slices, a surface in the receiver's own slice does not shadow it (the stated leak), the
// last step is exact; records stay finite and lookups in [0, 1] and non-increasing with many
// surfaces on one texel and extreme depth ranges; parameters are checked. The dsm pipeline and
// CPU/CUDA parity run with the other fixed-record storages (test_dsm_basis_storages.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "core/error.h"
#include "strategies/storage/dsm_storage.h"
#include "tests/strategies/storage/basis_test_support.h"

namespace dv {
namespace {

using test::BasisTexel;
using test::Nodes;
using test::Profile;

// A slab [2, 3] of extinction 2 fills every slice of the texel's range with 2 / S of optical
// depth; a lookup counts only the slices before its own, so it is short of the truth by less
// than one slice: |T' - T| < 1 - exp(-2 / S) everywhere, exact outside the range.
TEST(OccupancyStorage, ConstantSlabIsAStaircaseOfOneSlice) {
  const Profile slab{{{2.0, 3.0, 2.0}}, {}};
  for (int slices : {32, 64, 128}) {
    const std::string name = "occupancy" + std::to_string(slices);
    const BasisTexel texel(name, slab.nodes(0.01));
    const double bound = 1.0 - std::exp(-2.0 / slices);
    const test::ErrorFigures e = test::error_over(texel, slab, 1.5, 3.5);
    EXPECT_LE(e.max, bound + 1e-6) << name;
    EXPECT_GT(e.max, 0.5 * bound) << name << ": the staircase is there";
    EXPECT_EQ(texel.at(1.9f), 1.0) << name;
    EXPECT_NEAR(texel.at(3.1f), std::exp(-2.0), 1e-6) << name;
    RecordProperty("slab_max_error_" + name, std::to_string(e.max));
  }
}

// Translucent surfaces at z = 1 (alpha 0.5) and 1.5 (alpha 0.3) over an opaque floor at 3: 64
// slices of 1/32 each, the surfaces in slabs 0 and 1. Every lookup in a later slice is exact; on
// a surface (its own slice) the value before its step.
TEST(OccupancyStorage, SurfacesInSlicesOfTheirOwnAreExact) {
  const Nodes nodes = {{1.0f, 1.0f},  {1.0f, 0.5f},  {1.5f, 0.5f},
                       {1.5f, 0.35f}, {3.0f, 0.35f}, {3.0f, 0.0f}};
  const BasisTexel texel("occupancy64", nodes);
  EXPECT_EQ(texel.at(0.5f), 1.0);
  EXPECT_EQ(texel.at(1.0f), 1.0);
  EXPECT_NEAR(texel.at(1.25f), 0.5, 1e-6);
  EXPECT_NEAR(texel.at(1.5f), 0.5, 1e-6);
  EXPECT_NEAR(texel.at(2.0f), 0.35, 1e-6);
  EXPECT_NEAR(texel.at(2.999f), 0.35, 1e-6);  // on the floor: not shadowed by its own step
  EXPECT_NEAR(texel.at(3.5f), std::exp(-kMaxOpticalDepth), 1e-9);
}

// Two surfaces in one slab (slices 0 and 6 of slab 0): between them the slab map gives each
// occupied slice half the slab's optical depth, exp(-(tau_1 + tau_2) / 2), the paper's
// (1 - a)^n with one alpha for the slab; behind both it is exact again.
TEST(OccupancyStorage, SurfacesSharingASlabShareItsDepth) {
  const Nodes nodes = {{1.0f, 1.0f},  {1.0f, 0.5f},  {1.2f, 0.5f},
                       {1.2f, 0.35f}, {3.0f, 0.35f}, {3.0f, 0.0f}};
  const BasisTexel texel("occupancy64", nodes);
  const double tau = -std::log(0.5) - std::log(0.7);
  EXPECT_NEAR(texel.at(1.1f), std::exp(-tau / 2.0), 1e-6);
  EXPECT_NEAR(texel.at(2.0f), 0.35, 1e-6);
}

// A receiver behind a surface but in the same slice is not shadowed by it: slices of 1/32 over
// [1, 3], a sheet at 1.5 and receivers 1/100 behind it (slice 16) and 1/10 behind (slice 19).
TEST(OccupancyStorage, HardSurfaceInTheReceiversSliceDoesNotShadowIt) {
  const Nodes nodes = {{1.0f, 1.0f},  {1.0f, 0.5f},  {1.5f, 0.5f},
                       {1.5f, 0.25f}, {3.0f, 0.25f}, {3.0f, 0.0f}};
  const BasisTexel texel("occupancy64", nodes);
  EXPECT_NEAR(texel.at(1.51f), 0.5, 1e-6);  // truth 0.25: the stated leak
  EXPECT_NEAR(texel.at(1.6f), 0.25, 1e-6);
}

TEST(OccupancyStorage, HardManySurfacesOnOneTexelStayFiniteInRangeAndMonotone) {
  std::mt19937 rng(3);
  for (const auto& [near, far] : test::kExtremeRanges) {
    const Nodes nodes = test::many_surfaces(near, far, rng);
    for (const char* name : {"occupancy32", "occupancy64", "occupancy128"}) {
      const BasisTexel texel(name, nodes);
      for (int k = 0; k < kTexelHeaderFloats + test::kOccupancyTestSlabs; ++k)
        EXPECT_TRUE(std::isfinite(texel.record[size_t(k)])) << name;
      double previous = 1.0;
      for (int i = -10; i <= 1010; ++i) {
        const double t = texel.at(float(near + (far - near) * i / 1000.0));
        ASSERT_TRUE(t >= 0.0 && t <= 1.0) << name << " " << near << " " << i << ": " << t;
        ASSERT_LE(t, previous + 1e-6) << name << " " << near << " " << i;
        previous = t;
      }
    }
  }
}

TEST(OccupancyStorage, ParametersAreChecked) {
  EXPECT_THROW(storage_registry().create("occupancy", StrategyParams::parse({"slices=48"})),
               InputError);
  EXPECT_THROW(storage_registry().create("occupancy", StrategyParams::parse({"slices=256"})),
               InputError);
  EXPECT_THROW(storage_registry().create("occupancy", StrategyParams::parse({"slabs=3"})),
               InputError);
  const auto storage = storage_registry().create("occupancy");
  EXPECT_EQ(storage->params()["slices"], 64);
  EXPECT_EQ(storage->params()["slabs"], 4);
  EXPECT_EQ(storage->own_figures()["bytes_per_texel"], 36);
  EXPECT_EQ(storage_registry()
                .create("occupancy", StrategyParams::parse({"slices=128", "slabs=8"}))
                ->own_figures()["bytes_per_texel"],
            4 * (3 + 8 + 4));
}

}  // namespace
}  // namespace dv
