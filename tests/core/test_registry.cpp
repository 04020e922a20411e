// Registries: creation by case-insensitive name, unknown names list the known ones, unread
// parameters are rejected, and each family exists (storage and voxelizer may still be empty).
#include <gtest/gtest.h>

#include "dsm/storage/dsm_storage.h"
#include "strategies/shadow/shadow_method.h"
#include "strategies/voxelizer/voxelizer.h"

namespace dv {
namespace {

TEST(Registry, ShadowMethodsByName) {
  const auto names = shadow_registry().names();
  EXPECT_NE(std::find(names.begin(), names.end(), "none"), names.end());
  EXPECT_NE(std::find(names.begin(), names.end(), "reference"), names.end());
  EXPECT_EQ(shadow_registry().create("Reference")->name(), "reference");
  // The oracle reports its fixed accuracy as figures; it has no parameters to echo.
  EXPECT_TRUE(shadow_registry().create("reference")->stats().contains("tolerance"));
  EXPECT_TRUE(shadow_registry().create("reference")->params().empty());
}

TEST(Registry, UnknownNameListsKnownOnes) {
  try {
    shadow_registry().create("dsm-magic");
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("dsm-magic"), std::string::npos);
    EXPECT_NE(msg.find("reference"), std::string::npos);
    EXPECT_NE(msg.find("none"), std::string::npos);
  }
  EXPECT_THROW(storage_registry().create("chunked-magic"), InputError);
  EXPECT_NO_THROW(storage_registry().create("chunked"));
  EXPECT_THROW(voxelizer_registry().create("no-such-voxelizer"), InputError);
  EXPECT_NO_THROW(voxelizer_registry().create("sat"));
}

TEST(Registry, UnreadParametersAreErrors) {
  try {
    shadow_registry().create("none", StrategyParams::parse({"eps=0.05"}));
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("eps"), std::string::npos);
  }
  EXPECT_THROW(StrategyParams::parse({"novalue"}), InputError);
  StrategyParams p = StrategyParams::parse({"res=512", "name=x"});
  EXPECT_EQ(p.integer("res", 0), 512);
  EXPECT_EQ(p.string("name", ""), "x");
  EXPECT_NO_THROW(p.finish("test"));
  EXPECT_THROW(StrategyParams::parse({"res=abc"}).number("res", 0), InputError);
}

}  // namespace
}  // namespace dv
