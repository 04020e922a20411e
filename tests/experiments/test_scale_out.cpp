// Scale-out: LPT shard assignment (deterministic, balanced on known costs), costs from a previous
// run's timings, merge refusing shards planned differently and naming missing ones, the SLURM
// scripts (array size, shard command, merge job; sbatch faked on PATH to check the afterany
// dependency), and `--gpus 2 --backend cpu` worker processes giving the rows of a plain run.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "core/json_reader.h"
#include "experiments/harness/merge.h"
#include "experiments/harness/rows.h"
#include "experiments/harness/runner.h"
#include "experiments/harness/shard_plan.h"
#include "experiments/harness/slurm.h"
#include "experiments/harness/workers.h"
#include "experiments/source_paths.h"
#include "tests/support/scratch_dir.h"

namespace dv {
namespace {

namespace fs = std::filesystem;

const std::string kBinary = test::binary_dir() + "/bin/deepvox";

std::string small_suite() {
  const std::string scene = test::source_dir() + "/experiments/scenes/demo.json";
  return R"({"suite": "small", "repeat": 1, "experiments": [
    {"name": "methods", "kind": "shadow", "scene": ")" +
         scene + R"(", "strategy": "reference",
     "settings": {"width": 48, "height": 32, "probe_points": 40, "seed": 3, "images": 0}},
    {"name": "dsm", "kind": "shadow", "scene": ")" +
         scene + R"(", "strategy": "dsm", "params": {"res": 32}, "sweep": {"eps": [0.05, 0.1]},
     "settings": {"width": 48, "height": 32, "probe_points": 40, "seed": 3, "images": 0}},
    {"name": "voxels", "kind": "voxelize", "scene": ")" +
         scene + R"(", "strategy": ["exact", "sat"], "settings": {"res": "32"}}]})";
}

fs::path temp_dir(const std::string& name) {
  return test::scratch_dir("test_harness_tmp", name);
}

std::string read(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Rows without timings (unit ms); item, names, values and notes.
std::vector<std::string> untimed(const std::string& folder) {
  std::vector<std::string> out;
  for (const Row& r : read_rows_csv(folder + "/rows.csv"))
    if (r.unit != "ms") {
      std::ostringstream line;
      line.precision(17);
      line << r.item << "|" << r.experiment << "|" << r.strategy << "|" << r.params << "|"
           << r.metric << "|" << r.stat << "|" << r.value << "|" << r.unit << "|" << r.note;
      out.push_back(line.str());
    }
  return out;
}

std::vector<RunItem> items_with_costs(const std::vector<double>& costs, ItemCosts& out) {
  std::vector<RunItem> items(costs.size());
  for (size_t k = 0; k < costs.size(); ++k) {
    items[k].index = int(k);
    out.by_index[int(k)] = costs[k];
  }
  return items;
}

TEST(ShardPlan, LptIsBalancedAndDeterministicOnKnownCosts) {
  ItemCosts costs{"test", {}};
  // Counted round robin (index % 2) would give loads 18 and 4; LPT gives 11 and 11.
  const std::vector<RunItem> items = items_with_costs({7, 1, 5, 1, 4, 2, 2}, costs);
  const ShardPlan plan = plan_shards(items, costs, 2);
  EXPECT_EQ(plan.load, (std::vector<double>{11, 11}));
  // Largest first: 7 -> 1, 5 -> 2, 4 -> 2, 2 (item 5) -> 1, 2 (item 6) -> 1, 1 -> 2, 1 -> 2.
  EXPECT_EQ(plan.shard_of, (std::vector<int>{1, 2, 2, 2, 2, 1, 1}));
  const ShardPlan again = plan_shards(items, costs, 2);
  EXPECT_EQ(again.shard_of, plan.shard_of);
  EXPECT_EQ(again.hash, plan.hash);
  ItemCosts other = costs;
  other.by_index[1] = 8;  // another cost source plans differently, and its hash says so
  EXPECT_NE(plan_shards(items, other, 2).hash, plan.hash);
  // Three shards: 7 | 5 2 | 4 2 1, then the last 1 to the first of three equal loads.
  EXPECT_EQ(plan_shards(items, costs, 3).load, (std::vector<double>{8, 7, 7}));
}

TEST(ShardPlan, EstimateGrowsWithPixelsProbesAndVoxels) {
  RunItem a;
  a.kind = "shadow";
  a.strategy = "dsm";
  a.settings = {{"width", "320"}, {"height", "200"}, {"probe_points", "400"}};
  a.params = {{"res", "256"}};
  RunItem bigger = a;
  bigger.settings["width"] = "640";
  EXPECT_GT(estimated_cost(bigger), estimated_cost(a));
  RunItem reference = a;
  reference.strategy = "reference";
  EXPECT_DOUBLE_EQ(estimated_cost(reference), 4 * estimated_cost(a));
  RunItem vox;
  vox.kind = "voxelize";
  vox.settings = {{"res", "128x128x64"}};
  EXPECT_DOUBLE_EQ(estimated_cost(vox), 128.0 * 128 * 64);
  vox.settings = {{"res", "32"}};
  EXPECT_DOUBLE_EQ(estimated_cost(vox), 32.0 * 32 * 32);
}

class ScaleOut : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = temp_dir(::testing::UnitTest::GetInstance()->current_test_info()->name());
    suite_ = (dir_ / "small.json").string();
    std::ofstream(suite_) << small_suite();
  }
  SuiteOutcome run(const std::string& shard, const std::string& costs,
                   const std::string& out = "out") {
    SuiteOptions o;
    o.suite = suite_;
    o.backend = "cpu";
    o.out = (dir_ / out).string();
    o.shard = shard;
    o.costs = costs;
    o.progress = false;
    o.report = false;
    return run_suite(o);
  }
  fs::path dir_;
  std::string suite_;
};

TEST_F(ScaleOut, ShardsUseAPreviousRunsTimingsAndMergeRefusesMixedPlans) {
  const SuiteOutcome whole = run("", "");  // no earlier run: the estimate
  const Json whole_meta = parse_json_file(whole.folder + "/meta.json");
  EXPECT_EQ(whole_meta["shard"]["cost_source"], "estimate");
  const SuiteOutcome first = run("1/2", "");  // finds the whole run under --out
  EXPECT_EQ(parse_json_file(first.folder + "/meta.json")["shard"]["cost_source"], whole.folder);
  const SuiteOutcome second = run("2/2", whole.folder);
  const SuiteOutcome second_estimated = run("2/2", "estimate");
  // Planned from other costs: refused naming the reason.
  try {
    merge_shards({first.folder, second_estimated.folder}, "");
    ADD_FAILURE() << "mixed plans merged";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cost source"), std::string::npos) << e.what();
  }
  // Missing shards are named; with allow_missing the merged report names them.
  try {
    merge_shards({first.folder}, "");
    ADD_FAILURE() << "missing shard merged";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("missing shard(s) 2 of 2"), std::string::npos) << e.what();
  }
  const std::string partial = merge_shards({first.folder}, (dir_ / "partial").string(), true);
  EXPECT_EQ(parse_json_file(partial + "/meta.json")["missing_shards"], Json::array({2}));
  EXPECT_NE(read(fs::path(partial) / "report.md").find("missing shards: 2 of 2"),
            std::string::npos);
  // A shard of another commit: refused naming it.
  const fs::path other_commit = dir_ / "other-commit";
  fs::copy(second.folder, other_commit, fs::copy_options::recursive);
  Json meta_other = parse_json_file((other_commit / "meta.json").string());
  meta_other["run"]["git_sha"] = "0123456789ab";
  std::ofstream(other_commit / "meta.json") << meta_other.dump(1);
  try {
    merge_shards({first.folder, other_commit.string()}, "");
    ADD_FAILURE() << "shards of two commits merged";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("different commit"), std::string::npos) << e.what();
  }
  const std::string merged = merge_shards({second.folder, first.folder}, "");
  EXPECT_EQ(untimed(whole.folder), untimed(merged));
  const Json meta = parse_json_file(merged + "/meta.json");
  EXPECT_EQ(meta["scale_out"]["summary"], "2 CPU workers on 1 host");
  EXPECT_FALSE(meta["merged_from"][0]["run"]["host"].get<std::string>().empty());
  EXPECT_NE(read(fs::path(merged) / "report.md").find("- scale-out: 2 CPU workers on 1 host"),
            std::string::npos);
}

// The workers' cost source comes from the suite the caller loaded (workers.cpp loads the file
// once): the suite file may be gone by then, and an explicit --costs is passed on as is.
TEST_F(ScaleOut, CostSourceUsesTheLoadedSuiteWithoutReadingTheFile) {
  const Suite suite = load_suite(suite_);
  SuiteOptions o;
  o.suite = (dir_ / "no-such-suite.json").string();
  o.out = (dir_ / "out").string();
  EXPECT_EQ(fixed_cost_source(o, suite), "estimate");
  o.costs = "earlier/run";
  EXPECT_EQ(fixed_cost_source(o, suite), "earlier/run");
}

TEST_F(ScaleOut, SlurmScriptsRunTheArrayAndTheMergeAfterAny) {
  SuiteOptions o;
  o.suite = suite_;
  o.backend = "cpu";
  o.out = (dir_ / "out").string();
  SlurmOptions s;
  s.tasks = 3;
  s.partition = "gpu";
  s.time = "01:00:00";
  const SlurmScripts cpu = slurm_scripts(o, s, (dir_ / "session").string(), kBinary);
  EXPECT_NE(cpu.array.find("#SBATCH --array=1-3\n"), std::string::npos) << cpu.array;
  EXPECT_NE(cpu.array.find("#SBATCH --partition=gpu\n"), std::string::npos);
  EXPECT_NE(cpu.array.find("#SBATCH --time=01:00:00\n"), std::string::npos);
  EXPECT_EQ(cpu.array.find("gres"), std::string::npos);  // no GPU directive on the CPU
  EXPECT_NE(cpu.array.find("'suite' '" + fs::absolute(suite_).string() + "' '--shard' \"$task/3\""),
            std::string::npos)
      << cpu.array;
  EXPECT_NE(cpu.array.find("'--costs' 'estimate'"), std::string::npos);
  EXPECT_NE(cpu.merge.find("merge --allow-missing --out '" + o.out + "'"), std::string::npos)
      << cpu.merge;
  o.backend = "cuda";
  EXPECT_NE(slurm_scripts(o, s, "x", kBinary).array.find("#SBATCH --gres=gpu:1\n"),
            std::string::npos);

  // --submit through a fake sbatch that records its arguments and answers job ids.
  const fs::path bin = dir_ / "bin";
  fs::create_directories(bin);
  std::ofstream(bin / "sbatch") << "#!/bin/sh\necho \"$@\" >> " << (dir_ / "sbatch.log").string()
                                << "\necho $((4000 + $(wc -l < " << (dir_ / "sbatch.log").string()
                                << ")))\n";
  fs::permissions(bin / "sbatch", fs::perms::owner_all);
  const std::string path = bin.string() + ":" + std::getenv("PATH");
  const std::string command = "PATH=" + path + " " + kBinary + " suite " + suite_ +
                              " --backend cpu --slurm --gpus 2 --submit --out " +
                              (dir_ / "out").string() + " > " + (dir_ / "submit.txt").string();
  ASSERT_EQ(std::system(command.c_str()), 0) << read(dir_ / "submit.txt");
  const std::string log = read(dir_ / "sbatch.log");
  EXPECT_NE(log.find("--parsable "), std::string::npos) << log;
  EXPECT_NE(log.find("array.sbatch\n--parsable --dependency=afterany:4001 "), std::string::npos)
      << log;
  EXPECT_NE(read(dir_ / "submit.txt").find("array job 4001 (2 tasks) and merge job 4002"),
            std::string::npos);
  // --dry-run prints both scripts and writes nothing.
  const std::string dry = kBinary + " suite " + suite_ + " --backend cpu --slurm --gpus 2 " +
                          "--dry-run --out " + (dir_ / "dry").string() + " > " +
                          (dir_ / "dry.txt").string();
  ASSERT_EQ(std::system(dry.c_str()), 0);
  EXPECT_NE(read(dir_ / "dry.txt").find("#SBATCH --array=1-2"), std::string::npos);
  EXPECT_NE(read(dir_ / "dry.txt").find(" merge --allow-missing "), std::string::npos);
  EXPECT_FALSE(fs::exists(dir_ / "dry"));
}

TEST_F(ScaleOut, CpuWorkerProcessesGiveTheRowsOfAPlainRun) {
  const SuiteOutcome plain = run("", "estimate", "plain");
  const std::string command = kBinary + " suite " + suite_ + " --backend cpu --gpus 2 --out " +
                              (dir_ / "workers").string() + " > " +
                              (dir_ / "workers.txt").string() + " 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << read(dir_ / "workers.txt");
  std::string merged;
  for (const auto& entry : fs::directory_iterator(dir_ / "workers" / "small"))
    if (entry.path().string().find("-merged") != std::string::npos) merged = entry.path().string();
  ASSERT_FALSE(merged.empty()) << read(dir_ / "workers.txt");
  EXPECT_EQ(untimed(plain.folder), untimed(merged));
  const Json meta = parse_json_file(merged + "/meta.json");
  EXPECT_EQ(meta["merged_from"].size(), 2u);
  EXPECT_EQ(meta["done"], 5);
  EXPECT_EQ(meta["failed"], 0);
  EXPECT_EQ(meta["scale_out"]["summary"], "2 CPU workers on 1 host");
  // Each worker had half of the threads (DEEPVOX_THREADS) and its own status file.
  for (const Json& shard : meta["merged_from"]) {
    EXPECT_NE(shard["run"]["command_line"].get<std::string>().find("--status-file"),
              std::string::npos);
  }
}

}  // namespace
}  // namespace dv
