// Replays every committed fuzz input (tests/fuzz/corpus/<target>/: the seed corpus and each
// crasher the fuzzers found, kept as a regression input) through its entry point in the normal
// build: each must be accepted or rejected with an InputError, never crash or throw anything
// else (fuzz_entry.h). Under the `asan` preset this runs with the sanitizers.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "experiments/source_paths.h"
#include "tests/fuzz/fuzz_entry.h"

namespace dv {
namespace {

namespace fs = std::filesystem;

using Entry = int (*)(const uint8_t*, size_t);

void replay(const char* target, Entry entry) {
  const fs::path dir = fs::path(test::source_dir()) / "tests" / "fuzz" / "corpus" / target;
  int replayed = 0;
  for (const fs::directory_entry& e : fs::directory_iterator(dir)) {
    std::ifstream in(e.path(), std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    SCOPED_TRACE(e.path().string());
    EXPECT_NO_THROW(entry(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()));
    ++replayed;
  }
  EXPECT_GT(replayed, 0) << dir;
}

TEST(HardFuzzReplay, SceneJson) {
  replay("scene_json", fuzz::scene_json);
}
TEST(HardFuzzReplay, Gltf) {
  replay("gltf", fuzz::gltf);
}
TEST(HardFuzzReplay, Mesh) {
  replay("mesh", fuzz::mesh);
}
TEST(HardFuzzReplay, Suite) {
  replay("suite", fuzz::suite);
}

}  // namespace
}  // namespace dv
