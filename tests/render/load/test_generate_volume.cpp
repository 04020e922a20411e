// Tests of the JSON entry point generate_volume(): each generator through its spec, the
// default and overridden placement, raw paths relative to the scene folder, and the errors for
// unknown keys, unknown generators and bad parameters.
#include <gtest/gtest.h>

#include <fstream>

#include "core/error.h"
#include "render/io/volume_io.h"
#include "render/load/volume_generators.h"
#include "tests/support/scratch_dir.h"

namespace dv {
namespace {

VolumeGrid generate(const std::string& json_text, const std::string& scene_dir = "") {
  const Json json = Json::parse(json_text);
  JsonReader spec(json, "scene.json", "/volumes/0");
  return generate_volume(spec, scene_dir);
}

std::string error_of(const std::string& json_text, const std::string& scene_dir = "") {
  try {
    generate(json_text, scene_dir);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected an InputError for " << json_text;
  return "";
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(GenerateVolume, SheppLoganWithDefaultPlacement) {
  const VolumeGrid v = generate(R"({"generator": "shepp_logan", "dims": [9, 9, 5]})");
  EXPECT_EQ(v.density, make_shepp_logan_3d({9, 9, 5}).density);
  EXPECT_EQ(v.spacing, dvec3(1.0 / 8.0));         // largest extent is 1 unit
  EXPECT_EQ(v.origin, dvec3(-0.5, -0.5, -0.25));  // centred on the object origin
  EXPECT_EQ(v.bounds().center(), dvec3(0.0));
}

TEST(GenerateVolume, OriginAndSpacingOverride) {
  const VolumeGrid v = generate(
      R"({"generator": "block", "dims": [2, 3, 4], "density": 0.25,
          "origin": [1, 2, 3], "spacing": [0.5, 0.25, 2]})");
  EXPECT_EQ(v.origin, dvec3(1.0, 2.0, 3.0));
  EXPECT_EQ(v.spacing, dvec3(0.5, 0.25, 2.0));
  ASSERT_EQ(v.density.size(), size_t(24));
  EXPECT_EQ(v.density[17], 0.25f);
  const VolumeGrid full = generate(R"({"generator": "block", "dims": [1, 1, 1]})");
  EXPECT_EQ(full.density, std::vector<float>{1.0f});
  EXPECT_EQ(full.spacing, dvec3(1.0));
}

TEST(GenerateVolume, SmokeSeedAndTurbulence) {
  const VolumeGrid v =
      generate(R"({"generator": "smoke", "dims": [20, 24, 20], "seed": 7, "turbulence": 0.5})");
  EXPECT_EQ(v.density, make_smoke_plume({20, 24, 20}, 7, 0.5).density);
  const VolumeGrid default_seed = generate(R"({"generator": "smoke", "dims": [20, 24, 20]})");
  EXPECT_EQ(default_seed.density, make_smoke_plume({20, 24, 20}, 1, 1.0).density);
  EXPECT_TRUE(contains(error_of(R"({"generator": "smoke", "dims": [8, 8, 8], "seed": -1})"),
                       "/volumes/0/seed"));
  EXPECT_TRUE(contains(error_of(R"({"generator": "smoke", "dims": [8, 8, 8], "seed": 1.5})"),
                       "non-negative integer"));
  EXPECT_TRUE(contains(error_of(R"({"generator": "smoke", "dims": [8, 8, 8], "turbulence": -1})"),
                       "turbulence"));
}

TEST(GenerateVolume, RawPathResolvesAgainstSceneDir) {
  const auto dir = test::scratch_dir("test_volumes_tmp");
  std::filesystem::create_directories(dir / "data");
  {
    std::ofstream out(dir / "data" / "v.raw", std::ios::binary);
    const unsigned char bytes[8] = {0, 1, 0, 255, 0xff, 0xff, 0x80, 0x00};  // big endian uint16
    out.write(reinterpret_cast<const char*>(bytes), 8);
  }
  const std::string spec =
      R"({"generator": "raw", "dims": [2, 2, 1], "file": "data/v.raw", "type": "uint16",
          "big_endian": true})";
  const VolumeGrid v = generate(spec, dir.string());
  ASSERT_EQ(v.density.size(), size_t(4));
  EXPECT_FLOAT_EQ(v.density[0], 1.0f / 65535.0f);
  EXPECT_FLOAT_EQ(v.density[1], 255.0f / 65535.0f);
  EXPECT_EQ(v.density[2], 1.0f);
  EXPECT_FLOAT_EQ(v.density[3], 32768.0f / 65535.0f);
  EXPECT_EQ(v.spacing, dvec3(1.0));
  EXPECT_EQ(v.origin, dvec3(-0.5, -0.5, 0.0));
  EXPECT_EQ(v.name, (dir / "data" / "v.raw").string());

  // From another folder the same relative path is missing, and the error names it.
  const std::string message = error_of(spec, (dir / "elsewhere").string());
  EXPECT_TRUE(contains(message, (dir / "elsewhere" / "data" / "v.raw").string())) << message;
  // An absolute path ignores the scene folder.
  const std::string absolute =
      R"({"generator": "raw", "dims": [2, 2, 1], "type": "uint16", "file": ")" +
      (dir / "data" / "v.raw").string() + R"("})";
  EXPECT_EQ(generate(absolute, "/nonexistent").density.size(), size_t(4));
  EXPECT_TRUE(contains(
      error_of(R"({"generator": "raw", "dims": [2, 2, 1], "file": "data/v.raw", "type": "u16"})",
               dir.string()),
      "uint8, uint16, float32"));
}

TEST(GenerateVolume, UnknownKeysAndGenerators) {
  const std::string unknown_key =
      error_of(R"({"generator": "block", "dims": [2, 2, 2], "seed": 3})");
  EXPECT_TRUE(contains(unknown_key, "scene.json")) << unknown_key;
  EXPECT_TRUE(contains(unknown_key, "'seed'")) << unknown_key;
  EXPECT_TRUE(
      contains(error_of(R"({"generator": "shepp_logan", "dims": [4, 4, 4], "dim": 1})"), "'dim'"));

  const std::string unknown_generator = error_of(R"({"generator": "fog", "dims": [2, 2, 2]})");
  EXPECT_TRUE(contains(unknown_generator, "scene.json: /volumes/0/generator")) << unknown_generator;
  EXPECT_TRUE(contains(unknown_generator, "'fog'")) << unknown_generator;
  for (const std::string& name : volume_generator_names()) {
    EXPECT_TRUE(contains(unknown_generator, name)) << unknown_generator;
  }
  EXPECT_EQ(volume_generator_names().size(), 5u);
}

TEST(GenerateVolume, BadDimsAndPlacement) {
  const std::string zero = error_of(R"({"generator": "block", "dims": [2, 0, 2]})");
  EXPECT_TRUE(contains(zero, "zero-size volume")) << zero;
  EXPECT_TRUE(contains(zero, "scene.json: /volumes/0/dims")) << zero;
  EXPECT_TRUE(contains(error_of(R"({"generator": "block"})"), "/volumes/0/dims"));
  EXPECT_TRUE(contains(error_of(R"({"generator": "block", "dims": [2, 2]})"), "dims"));
  EXPECT_TRUE(contains(error_of(R"({"generator": "block", "dims": [100000, 100000, 100000]})"),
                       "too large"));
  EXPECT_TRUE(contains(
      error_of(R"({"generator": "block", "dims": [2, 2, 2], "spacing": [1, -1, 1]})"), "spacing"));
  EXPECT_TRUE(
      contains(error_of(R"({"generator": "block", "dims": [2, 2, 2], "density": 2})"), "density"));
  EXPECT_TRUE(contains(error_of(R"({"dims": [2, 2, 2]})"), "generator"));
}

}  // namespace
}  // namespace dv
