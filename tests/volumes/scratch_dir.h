// A fresh scratch folder per test (under the build tree) for the raw-file tests, so tests that
// CTest runs in parallel never share files.
#pragma once

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

inline std::filesystem::path volume_test_scratch_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path dir = std::filesystem::path(DEEPVOX_BINARY_DIR) / "test_volumes_tmp" /
                                    (std::string(info->test_suite_name()) + "." + info->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}
