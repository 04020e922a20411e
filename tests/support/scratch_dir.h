// A fresh, empty scratch folder per test under the build tree (AREA/NAME, NAME by default the
// running test's "Suite.Test"), so tests that CTest runs in parallel never share files.
#pragma once

#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include "experiments/source_paths.h"

namespace dv::test {

inline std::filesystem::path scratch_dir(const std::string& area, const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(test::binary_dir()) / area / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

inline std::filesystem::path scratch_dir(const std::string& area) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  return scratch_dir(area, std::string(info->test_suite_name()) + "." + info->name());
}

}  // namespace dv::test
