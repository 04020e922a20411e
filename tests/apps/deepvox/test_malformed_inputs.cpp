// The bad-input corpus (tests/data/malformed/, README there): every file is given to the
// deepvox command that reads it and must be rejected with exit code 2 and an error naming it
// (or the file it names), never a crash, except the few with a stated outcome; binvox files,
// which no command reads, go through read_binvox and must raise an InputError naming them.
// The fuzzers' regression inputs (tests/fuzz/corpus/*/crash-*) replay through test_fuzz_replay.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "core/error.h"
#include "experiments/source_paths.h"
#include "render/io/binvox.h"
#include "render/io/vdb_io.h"
#include "tests/apps/deepvox/cli_run.h"

namespace dv {
namespace {

namespace fs = std::filesystem;

fs::path corpus_dir() {
  return fs::path(test::source_dir()) / "tests" / "data" / "malformed";
}

// Every corpus file a command reads, as "folder/name" (raw data named by volume scenes and the
// README are not inputs of their own).
std::vector<std::string> corpus_files() {
  std::vector<std::string> out;
  for (const char* folder : {"scenes", "gltf", "meshes", "volumes", "suites", "points", "binvox"})
    for (const fs::directory_entry& e : fs::directory_iterator(corpus_dir() / folder)) {
      const std::string ext = e.path().extension().string();
      if (std::string(folder) == "volumes" && ext != ".json") continue;
      out.push_back(std::string(folder) + "/" + e.path().filename().string());
    }
  std::sort(out.begin(), out.end());
  return out;
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The names an error about `file` may carry: the file's, and the file it names (a volume
// scene's raw file, a scene's missing import).
std::vector<std::string> acceptable_names(const fs::path& file) {
  std::vector<std::string> names = {file.filename().string()};
  std::smatch m;
  const std::string text = read_text(file);
  if (std::regex_search(text, m, std::regex(R"re("(file|import)": "([^"]+)")re")))
    names.push_back(m[2]);
  return names;
}

// Files with a stated outcome other than exit 2: an empty points file is zero points (exit 0,
// an empty result), and a suite's experiment naming a missing scene or an unknown strategy is
// recorded as a failed experiment naming the problem while the suite goes on (exit 3, README
// "Experiment suites").
struct StatedOutcome {
  const char* file;
  int exit_code;
  const char* message;
};
constexpr StatedOutcome kStatedOutcomes[] = {
    {"points/empty.csv", 0, "0 points"},
    {"suites/missing-scene.json", 3, "no-such-scene.json: file not found"},
    {"suites/unknown-strategy.json", 3, "shadow method 'magic' not found"},
};

// Files whose error must also say what is wrong. A deepvox without OpenVDB (the lean build;
// this test links OpenVDB exactly when bin/deepvox does) says that instead.
struct StatedProblem {
  const char* file;
  const char* message;
};
constexpr StatedProblem kStatedProblems[] = {
    {"volumes/vdb-int-grid.json", "holds int32 values"},
    {"volumes/vdb-missing-grid.json",
     "no grid named 'density' (grids in the file: 'temperature' (float))"},
    {"volumes/vdb-truncated.json", "not a readable OpenVDB file"},
};

class HardMalformedInputs : public ::testing::TestWithParam<std::string> {};

TEST_P(HardMalformedInputs, RejectedWithExitTwoNamingTheFile) {
  const fs::path file = corpus_dir() / GetParam();
  const std::string folder = fs::path(GetParam()).parent_path().string();
  const fs::path scratch = fs::path(test::binary_dir()) / "test_malformed_tmp" / GetParam();
  fs::remove_all(scratch);
  fs::create_directories(scratch);
  if (folder == "binvox") {
    try {
      read_binvox(file.string());
      FAIL() << "read_binvox accepted " << file;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(file.filename().string()), std::string::npos)
          << e.what();
    }
    return;
  }
  std::string args;
  if (folder == "suites")
    args = "suite '" + file.string() + "' --backend cpu --out '" + scratch.string() + "'";
  else if (folder == "points")
    args = "probe '" + test::source_dir() +
           "/experiments/scenes/demo.json' --backend cpu --points '" + file.string() + "' --out '" +
           (scratch / "t.csv").string() + "'";
  else
    args = "info '" + file.string() + "'";
  const CommandResult r = run(args);
  for (const StatedOutcome& stated : kStatedOutcomes)
    if (GetParam() == stated.file) {
      EXPECT_EQ(r.exit_code, stated.exit_code) << args << "\n" << r.output;
      EXPECT_NE(r.output.find(stated.message), std::string::npos) << r.output;
      return;
    }
  EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
  EXPECT_NE(r.output.find("error"), std::string::npos) << r.output;
  const std::vector<std::string> names = acceptable_names(file);
  EXPECT_TRUE(
      std::any_of(names.begin(), names.end(),
                  [&](const std::string& n) { return r.output.find(n) != std::string::npos; }))
      << "the error does not name " << file.filename() << ":\n"
      << r.output;
  for (const StatedProblem& stated : kStatedProblems) {
    if (GetParam() != stated.file) continue;
    const char* message = vdb_supported() ? stated.message : "built without OpenVDB";
    EXPECT_NE(r.output.find(message), std::string::npos) << r.output;
  }
}

struct CorpusName {
  std::string operator()(const ::testing::TestParamInfo<std::string>& info) const {
    std::string n = info.param;
    for (char& ch : n) ch = std::isalnum(static_cast<unsigned char>(ch)) ? ch : '_';
    return n;
  }
};

INSTANTIATE_TEST_SUITE_P(Corpus, HardMalformedInputs, ::testing::ValuesIn(corpus_files()),
                         CorpusName());

}  // namespace
}  // namespace dv
