// Tests of raw volume files: round trips for uint8, uint16 (both byte orders) and float32,
// normalisation, centring, and the errors for wrong sizes, empty dims, missing files,
// non-finite samples and unknown type names.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <vector>

#include "core/error.h"
#include "render/io/volume_io.h"
#include "tests/support/scratch_dir.h"

namespace dv {
namespace {

void write_bytes(const std::string& path, const std::vector<unsigned char>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  ASSERT_TRUE(out.good()) << path;
}

// Runs f and returns the InputError message it throws ("" and a test failure if none).
template <class F>
std::string input_error_message(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected an InputError";
  return "";
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(RawVolume, Uint8NormalisedAndCentred) {
  const std::string path = (test::scratch_dir("test_volumes_tmp") / "u8.raw").string();
  std::vector<unsigned char> bytes(12);
  for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = (unsigned char)(i * 23);
  bytes[11] = 255;
  write_bytes(path, bytes);
  const VolumeGrid v = load_raw_volume(path, {3, 2, 2}, RawType::uint8, {0.5, 1.0, 2.0});
  ASSERT_EQ(v.density.size(), size_t(12));
  for (size_t i = 0; i < 11; ++i) EXPECT_FLOAT_EQ(v.density[i], float(i * 23) / 255.0f) << i;
  EXPECT_EQ(v.density[11], 1.0f);
  EXPECT_EQ(v.dims, ivec3(3, 2, 2));
  EXPECT_EQ(v.spacing, dvec3(0.5, 1.0, 2.0));
  EXPECT_EQ(v.origin, dvec3(-0.5, -0.5, -1.0));
  EXPECT_EQ(v.name, path);
}

TEST(RawVolume, Uint16BothByteOrders) {
  const auto dir = test::scratch_dir("test_volumes_tmp");
  const std::vector<uint16_t> values = {0, 1, 0x0102, 32768, 65534, 65535};
  std::vector<unsigned char> little, big;
  for (uint16_t v : values) {
    little.push_back((unsigned char)(v & 0xff));
    little.push_back((unsigned char)(v >> 8));
    big.push_back((unsigned char)(v >> 8));
    big.push_back((unsigned char)(v & 0xff));
  }
  write_bytes((dir / "le.raw").string(), little);
  write_bytes((dir / "be.raw").string(), big);
  const VolumeGrid le =
      load_raw_volume((dir / "le.raw").string(), {1, 2, 3}, RawType::uint16, dvec3(1.0), false);
  const VolumeGrid be =
      load_raw_volume((dir / "be.raw").string(), {1, 2, 3}, RawType::uint16, dvec3(1.0), true);
  for (size_t i = 0; i < values.size(); ++i) {
    EXPECT_FLOAT_EQ(le.density[i], float(values[i]) / 65535.0f) << i;
    EXPECT_EQ(le.density[i], be.density[i]) << i;
  }
  EXPECT_EQ(le.density.back(), 1.0f);
  // Read with the wrong byte order, 0x0102 becomes 0x0201.
  const VolumeGrid swapped =
      load_raw_volume((dir / "le.raw").string(), {1, 2, 3}, RawType::uint16, dvec3(1.0), true);
  EXPECT_FLOAT_EQ(swapped.density[2], float(0x0201) / 65535.0f);
}

TEST(RawVolume, Float32RoundTripAndBigEndian) {
  const auto dir = test::scratch_dir("test_volumes_tmp");
  VolumeGrid original;
  original.name = "test";
  original.dims = {4, 3, 2};
  for (int i = 0; i < 24; ++i) original.density.push_back(float(i) / 23.0f - 0.01f * float(i % 3));
  save_raw_volume((dir / "f32.raw").string(), original);
  EXPECT_EQ(std::filesystem::file_size(dir / "f32.raw"), 96u);
  const VolumeGrid loaded =
      load_raw_volume((dir / "f32.raw").string(), {4, 3, 2}, RawType::float32, dvec3(0.25));
  EXPECT_EQ(loaded.density, original.density);

  std::vector<unsigned char> big;
  for (float f : {0.5f, 1.0f, -2.25f}) {
    uint32_t bits;
    std::memcpy(&bits, &f, 4);
    for (int b = 3; b >= 0; --b) big.push_back((unsigned char)(bits >> (8 * b)));
  }
  write_bytes((dir / "be.raw").string(), big);
  const VolumeGrid be =
      load_raw_volume((dir / "be.raw").string(), {3, 1, 1}, RawType::float32, dvec3(1.0), true);
  EXPECT_EQ(be.density, (std::vector<float>{0.5f, 1.0f, -2.25f}));
}

TEST(RawVolume, WrongFileSizeNamesFileAndBothSizes) {
  const std::string path = (test::scratch_dir("test_volumes_tmp") / "short.raw").string();
  write_bytes(path, std::vector<unsigned char>(23));
  const std::string message = input_error_message([&] {
    load_raw_volume(path, {3, 2, 2}, RawType::uint16, dvec3(1.0));
  });
  EXPECT_TRUE(contains(message, path)) << message;
  EXPECT_TRUE(contains(message, "23 bytes")) << message;
  EXPECT_TRUE(contains(message, "24 bytes")) << message;
  // One byte too many is just as wrong.
  write_bytes(path, std::vector<unsigned char>(25));
  EXPECT_TRUE(contains(input_error_message([&] {
                         load_raw_volume(path, {3, 2, 2}, RawType::uint16, dvec3(1.0));
                       }),
                       "25 bytes"));
}

TEST(RawVolume, ZeroDimsMissingFileAndBadValues) {
  const auto dir = test::scratch_dir("test_volumes_tmp");
  const std::string path = (dir / "v.raw").string();
  write_bytes(path, std::vector<unsigned char>(8));
  EXPECT_TRUE(contains(input_error_message([&] {
                         load_raw_volume(path, {0, 2, 4}, RawType::uint8, dvec3(1.0));
                       }),
                       "zero-size volume"));
  EXPECT_TRUE(contains(input_error_message([&] {
                         load_raw_volume(path, {2, -2, -2}, RawType::uint8, dvec3(1.0));
                       }),
                       "zero-size volume"));
  EXPECT_THROW(load_raw_volume(path, {2, 2, 2}, RawType::uint8, {1.0, 0.0, 1.0}), InputError);

  const std::string missing = (dir / "nope.raw").string();
  const std::string message = input_error_message([&] {
    load_raw_volume(missing, {2, 2, 2}, RawType::uint8, dvec3(1.0));
  });
  EXPECT_TRUE(contains(message, missing)) << message;

  EXPECT_TRUE(contains(input_error_message([&] {
                         load_raw_volume(dir.string(), {2, 2, 2}, RawType::uint8, dvec3(1.0));
                       }),
                       dir.string()));

  for (float bad : {std::nanf(""), INFINITY}) {
    std::vector<unsigned char> bytes(8, 0);
    uint32_t bits;
    std::memcpy(&bits, &bad, 4);
    for (int b = 0; b < 4; ++b) bytes[4 + size_t(b)] = (unsigned char)(bits >> (8 * b));
    write_bytes(path, bytes);
    const std::string nan_message = input_error_message([&] {
      load_raw_volume(path, {2, 1, 1}, RawType::float32, dvec3(1.0));
    });
    EXPECT_TRUE(contains(nan_message, path)) << nan_message;
    EXPECT_TRUE(contains(nan_message, "(1, 0, 0)")) << nan_message;
  }
}

TEST(RawVolume, ParseRawTypeListsTheKnownNames) {
  EXPECT_EQ(parse_raw_type("uint8", "x"), RawType::uint8);
  EXPECT_EQ(parse_raw_type("uint16", "x"), RawType::uint16);
  EXPECT_EQ(parse_raw_type("float32", "x"), RawType::float32);
  EXPECT_EQ(raw_type_size(RawType::uint16), 2);
  const std::string message =
      input_error_message([] { parse_raw_type("int16", "scene.json: /volumes/0/type"); });
  EXPECT_TRUE(contains(message, "scene.json: /volumes/0/type")) << message;
  EXPECT_TRUE(contains(message, "int16")) << message;
  EXPECT_TRUE(contains(message, "uint8, uint16, float32")) << message;
}

TEST(RawVolume, SaveRejectsMismatchedDensityCount) {
  VolumeGrid v;
  v.dims = {2, 2, 2};
  v.density.assign(7, 0.5f);
  EXPECT_THROW(save_raw_volume((test::scratch_dir("test_volumes_tmp") / "bad.raw").string(), v),
               InputError);
}

}  // namespace
}  // namespace dv
