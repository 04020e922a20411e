// Fixture of the harness tests that run suites: a fresh scratch folder per test (named after
// the test), files written into it, and suite options for a quiet CPU run whose results go
// into the folder's out/ (each test sets the rest: shard, smoke, only, repeat).
#pragma once

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "experiments/harness/runner.h"
#include "tests/support/scratch_dir.h"

namespace dv::test {

class HarnessTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = scratch_dir("test_harness_tmp",
                       ::testing::UnitTest::GetInstance()->current_test_info()->name());
  }
  std::string write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return (dir_ / name).string();
  }
  SuiteOptions cpu_options(const std::string& suite) const {
    SuiteOptions o;
    o.suite = suite;
    o.backend = "cpu";
    o.out = (dir_ / "out").string();
    o.progress = false;
    return o;
  }
  std::filesystem::path dir_;
};

}  // namespace dv::test
