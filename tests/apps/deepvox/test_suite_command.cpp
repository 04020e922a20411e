// Which options of `deepvox suite` go together (apps/deepvox/suite_command.h), without CLI11 and
// without running a suite: each rule refuses its combination naming the option, and every
// allowed combination picks its way of running.
#include <gtest/gtest.h>

#include <string>

#include "apps/deepvox/suite_command.h"
#include "core/error.h"

namespace dv::cli {
namespace {

SuiteCommand named(const std::string& suite) {
  SuiteCommand c;
  c.suite.suite = suite;
  return c;
}

// The option the InputError names (the text before its ": "), or "" when the command is
// accepted.
std::string refused_option(const SuiteCommand& c) {
  try {
    suite_mode(c);
  } catch (const InputError& e) {
    const std::string message = e.what();
    return message.substr(0, message.find(": "));
  }
  return "";
}

TEST(SuiteCommand, EachAllowedCombinationPicksItsMode) {
  SuiteCommand c = named("quick");
  EXPECT_EQ(suite_mode(c), SuiteMode::single);
  c.suite.shard = "2/3";
  EXPECT_EQ(suite_mode(c), SuiteMode::single);
  c = named("quick");
  c.gpus = "all";
  EXPECT_EQ(suite_mode(c), SuiteMode::workers);
  c = named("quick");
  c.runs = 3;
  EXPECT_EQ(suite_mode(c), SuiteMode::rounds);
  c = named("quick");
  c.use_slurm = true;
  c.gpus = "4";
  c.slurm.partition = "gpu";
  c.slurm.dry_run = true;
  EXPECT_EQ(suite_mode(c), SuiteMode::slurm);
  SuiteCommand list;
  list.list = true;
  EXPECT_EQ(suite_mode(list), SuiteMode::list);  // no suite needed
}

TEST(SuiteCommand, ResumeTakesAFolderInsteadOfASuite) {
  SuiteCommand c;
  c.suite.resume = true;
  c.suite.resume_dir = "out/suites/quick/2026-12-01_120000_abc1234";
  c.suite.force = true;
  EXPECT_EQ(suite_mode(c), SuiteMode::single);
  c.gpus = "2";
  EXPECT_EQ(suite_mode(c), SuiteMode::workers);
  c.suite.resume_dir.clear();  // the newest unfinished run of which suite?
  EXPECT_EQ(refused_option(c), "suite");
}

TEST(SuiteCommand, RefusesOptionsThatDoNotGoTogether) {
  EXPECT_EQ(refused_option(SuiteCommand{}), "suite");
  SuiteCommand c = named("quick");
  c.suite.force = true;
  EXPECT_EQ(refused_option(c), "--force");
  for (const auto& with_runs : {"resume", "slurm", "gpus", "shard"}) {
    c = named("quick");
    c.runs = 3;
    const std::string option = with_runs;
    if (option == "resume") c.suite.resume = true;
    if (option == "slurm") c.use_slurm = true;
    if (option == "gpus") c.gpus = "2";
    if (option == "shard") c.suite.shard = "1/2";
    EXPECT_EQ(refused_option(c), "--runs") << "--runs with --" << option;
  }
  c = named("quick");
  c.use_slurm = true;
  c.gpus = "all";
  EXPECT_EQ(refused_option(c), "--gpus all");
  for (int which = 0; which < 4; ++which) {
    c = named("quick");
    if (which == 0) c.slurm.submit = true;
    if (which == 1) c.slurm.dry_run = true;
    if (which == 2) c.slurm.partition = "gpu";
    if (which == 3) c.slurm.time = "02:00:00";
    EXPECT_EQ(refused_option(c), "--submit/--dry-run/--partition/--time") << which;
  }
  c = named("quick");
  c.gpus = "2";
  c.suite.shard = "1/2";
  EXPECT_EQ(refused_option(c), "--gpus");
}

// --protocol replicate: rounds of at least 5 runs (5 when --runs is not given), never beside the
// options of one folder; --order-seed orders one whole run.
TEST(SuiteCommand, ReplicateProtocolRunsAtLeastFiveRounds) {
  SuiteCommand c = named("quick");
  c.protocol = "replicate";
  EXPECT_EQ(suite_mode(c), SuiteMode::rounds);
  EXPECT_EQ(round_count(c), kReplicateRuns);
  c.runs = 8;
  EXPECT_EQ(round_count(c), 8);
  c.runs = 3;
  EXPECT_EQ(refused_option(c), "--protocol replicate");
  c = named("quick");
  c.protocol = "shuffle";
  EXPECT_EQ(refused_option(c), "--protocol");
  for (const auto& beside : {"resume", "slurm", "gpus", "shard"}) {
    const std::string option = beside;
    for (const bool protocol : {true, false}) {
      c = named("quick");
      if (protocol)
        c.protocol = "replicate";
      else
        c.order_seed_given = true;
      if (option == "resume") c.suite.resume = true;
      if (option == "slurm") c.use_slurm = true;
      if (option == "gpus") c.gpus = "2";
      if (option == "shard") c.suite.shard = "1/2";
      EXPECT_EQ(refused_option(c), protocol ? "--protocol" : "--order-seed") << option;
    }
  }
  c = named("quick");
  c.order_seed_given = true;
  EXPECT_EQ(suite_mode(c), SuiteMode::single);
  EXPECT_EQ(round_count(c), 0);
}

}  // namespace
}  // namespace dv::cli
