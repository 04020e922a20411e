// Fixture of the harness tests that run suites: a fresh scratch folder per test (named after
// the test), files written into it, and suite options for a quiet CPU run whose results go
// into the folder's out/ (each test sets the rest: shard, smoke, only, repeat); and the rows of
// a run without its timings, to compare two runs.
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "experiments/harness/rows.h"
#include "experiments/harness/runner.h"
#include "tests/support/scratch_dir.h"

namespace dv::test {

// Rows without timings (unit ms), which differ from run to run, as comparable lines.
inline std::vector<std::string> untimed(const std::vector<Row>& rows) {
  std::vector<std::string> out;
  for (const Row& r : rows)
    if (r.unit != "ms") {
      std::ostringstream line;
      line.precision(17);
      line << r.item << "|" << r.experiment << "|" << r.scene << "|" << r.strategy << "|"
           << r.params << "|" << r.metric << "|" << r.stat << "|" << r.value << "|" << r.unit << "|"
           << r.note;
      out.push_back(line.str());
    }
  return out;
}

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
