// Registries: creation by case-insensitive name, unknown names list the known ones, unread
// parameters are rejected, each family exists; parameter tables check values, fill defaults
// and echo them typed.
#include <gtest/gtest.h>

#include "strategies/shadow/shadow_method.h"
#include "strategies/storage/dsm_storage.h"
#include "strategies/voxelizer/voxelizer.h"

namespace dv {
namespace {

TEST(Registry, ShadowMethodsByName) {
  const auto names = shadow_registry().names();
  EXPECT_NE(std::find(names.begin(), names.end(), "none"), names.end());
  EXPECT_NE(std::find(names.begin(), names.end(), "reference"), names.end());
  EXPECT_EQ(shadow_registry().create("Reference")->name(), "reference");
  // The oracle reports its fixed accuracy as figures; it has no parameters to echo.
  EXPECT_TRUE(shadow_registry().create("reference")->stats().contains("volume_integral"));
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

// A table of every kind of parameter, resolved and echoed.
const ParamTable& example_table() {
  static const ParamTable table = {
      integer_param("res", 1024, 1, 65536, "texels per side"),
      positive_param("scale", 1.0, "positive factor"),
      multiple_param("layers", 256, 8, 8, 65536, "layers"),
      integer_choice_param("bits", 64, {32, 64, 128}, "bits"),
      choice_param("filter", "none", {"none", "bilinear"}, "lookup"),
      name_param("storage", "compact", "storage strategy"),
      nested_param("storage", "a parameter of the storage"),
      derived(number_param("bias", 0.0, 0.0, 1.0, "derived from bits")),
  };
  return table;
}

TEST(ParamTables, DefaultsAreFilledAndEchoedTyped) {
  const StrategyParams p = StrategyParams::parse({"res=512"}).resolved(example_table(), "test");
  EXPECT_EQ(p.integer("res"), 512);
  EXPECT_EQ(p.number("scale"), 1.0);
  EXPECT_EQ(p.integer("layers"), 256);
  EXPECT_EQ(p.string("filter"), "none");
  EXPECT_EQ(p.number("bias", 0.25), 0.25);  // derived: the strategy's fallback, echoed
  const nlohmann::json echo = p.echo();
  EXPECT_EQ(echo, nlohmann::json({{"res", 512},
                                  {"scale", 1.0},
                                  {"layers", 256},
                                  {"bits", 64},
                                  {"filter", "none"},
                                  {"storage", "compact"},
                                  {"bias", 0.25}}));
  EXPECT_TRUE(echo["res"].is_number_integer());
  EXPECT_TRUE(echo["scale"].is_number_float());
}

TEST(ParamTables, ValuesOutsideTheirRangeNameTheKey) {
  const auto rejects = [](const std::string& item, const std::string& words) {
    try {
      StrategyParams::parse({item}).resolved(example_table(), "test strategy");
      ADD_FAILURE() << item << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  rejects("res=0", "[1, 65536]");
  rejects("res=1.5", "an integer");
  rejects("res=abc", "an integer");
  rejects("scale=0", "> 0");
  rejects("scale=nan", "a number");
  rejects("layers=12", "a multiple of 8");
  rejects("bits=48", "32 | 64 | 128");
  rejects("filter=cubic", "none | bilinear");
  rejects("bias=1.5", "[0, 1]");
  rejects("nope=1", "unknown parameter 'nope' (known: res, scale");
  rejects("storagealloc=1", "unknown parameter");
  EXPECT_NO_THROW(StrategyParams::parse({"storage.alloc=thesis", "bits=128", "layers=16"})
                      .resolved(example_table(), "test"));
}

TEST(ParamTables, EveryRegisteredDefaultPassesItsOwnCheck) {
  const auto check = [](const auto& registry) {
    for (const std::string& name : registry.names())
      for (const ParamSpec& spec : registry.params(name)) {
        EXPECT_FALSE(spec.description.empty()) << name << " " << spec.key;
        if (!spec.fallback.empty())
          EXPECT_NO_THROW(spec.check(spec.fallback, name)) << name << " " << spec.key;
      }
  };
  check(shadow_registry());
  check(storage_registry());
  check(voxelizer_registry());
}

TEST(ParamTables, ADeclaredKeyItsStrategyNeverReadsIsAnError) {
  Registry<Voxelizer> registry("voxelizer");
  registry.add("lazy", "reads nothing", {integer_param("unused", 1, 0, 9, "never read")},
               [](const StrategyParams&) -> std::unique_ptr<Voxelizer> { return nullptr; });
  EXPECT_THROW(registry.create("lazy"), Error);
}

}  // namespace
}  // namespace dv
