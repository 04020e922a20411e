// The fixture of the tests that run the deepvox executable (test_cli.cpp, test_cli_errors.cpp):
// a fresh folder per test under the build tree, files written there, and a clean failure's
// check; kSmallScene, a floor with a glass box under an omni light.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <string>

#include "experiments/source_paths.h"
#include "tests/apps/deepvox/cli_run.h"

namespace dv {

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::path(test::binary_dir()) / "test_cli_tmp" / info->name();
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  std::string write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return (dir_ / name).string();
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  // Expects a clean failure whose message contains every fragment.
  void expect_error(const std::string& args, std::initializer_list<std::string> fragments) {
    const CommandResult r = run(args);
    EXPECT_NE(r.exit_code, 0) << r.output;
    EXPECT_LT(r.exit_code, 128) << "crashed: " << r.output;
    EXPECT_NE(r.output.find("error"), std::string::npos) << r.output;
    for (const std::string& f : fragments)
      EXPECT_NE(r.output.find(f), std::string::npos) << "missing '" << f << "' in: " << r.output;
  }
  std::filesystem::path dir_;
};

inline const std::string kSmallScene = R"({
  "camera": {"position": [0, 1, 4], "target": [0, 0.3, 0], "width": 40, "height": 30},
  "lights": [{"type": "omni", "position": [0.5, 3, 0.5], "intensity": 9}],
  "objects": [
    {"mesh": {"generator": "box", "min": [-2, -0.1, -2], "max": [2, 0, 2]}},
    {"name": "glass", "mesh": {"generator": "box", "size": 0.6}, "transform": {"translate": [0, 0.6, 0]},
     "material": {"alpha": 0.4}, "interior": {"type": "constant", "sigma": 1.5}}
  ]
})";

}  // namespace dv
