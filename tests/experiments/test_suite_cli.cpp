// `deepvox suite | merge | report` as commands: the suite list, exit code 2 naming the file for
// a bad suite file, Ctrl-C sent to a running suite (exit 130, rows and a report of what was
// done), and `--runs N` (N child processes, one report whose intervals pool them).
#include <gtest/gtest.h>

#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "experiments/source_paths.h"
#include "tests/support/scratch_dir.h"

extern char** environ;

namespace dv {
namespace {

namespace fs = std::filesystem;

const std::string kBinary = test::binary_dir() + "/bin/deepvox";

struct CommandResult {
  int exit_code;
  std::string output;
};

CommandResult run(const std::string& args) {
  FILE* pipe = popen((kBinary + " " + args + " 2>&1").c_str(), "r");
  std::string out;
  char buf[4096];
  while (size_t n = fread(buf, 1, sizeof buf, pipe)) out.append(buf, n);
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status), out};
}

fs::path temp_dir(const std::string& name) {
  return test::scratch_dir("test_harness_tmp", name);
}

TEST(SuiteCli, ListShowsTheBuiltInSuitesWithADescription) {
  const CommandResult r = run("suite --list");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("quick "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("one page"), std::string::npos) << r.output;
}

TEST(SuiteCli, BadSuiteFileExitsTwoNamingTheFileAndTheProblem) {
  const fs::path dir = temp_dir("cli_bad");
  const fs::path bad = dir / "bad-suite.json";
  std::ofstream(bad) << R"({"suite": "x", "experiments": [{"name": "a", "kind": "shadw",
                           "scene": "s", "strategy": "none"}]})";
  const CommandResult r = run("suite " + bad.string() + " --out " + (dir / "out").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("bad-suite.json"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("unknown experiment kind 'shadw'"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "out")) << "no result folder for a bad file";
  EXPECT_EQ(run("suite no-such-suite").exit_code, 2);
  EXPECT_EQ(run("report " + dir.string()).exit_code, 2);
  EXPECT_EQ(run("merge " + dir.string()).exit_code, 2);
}

// A claim that names no timer stops the suite before anything runs, naming the claim.
TEST(SuiteCli, ClaimWithoutATimerExitsTwoNamingTheClaim) {
  const fs::path dir = temp_dir("cli_no_timer");
  const fs::path bad = dir / "no-timer.json";
  std::ofstream(bad) << R"({"suite": "x", "experiments": [{"name": "a", "kind": "shadow",
    "scene": "s", "strategy": "none",
    "findings": [{"claim": "none generates fast", "lower": ["", "generate_ms"],
                  "than": ["", "generate_ms"]}]}]})";
  const CommandResult r = run("suite " + bad.string() + " --out " + (dir / "out").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("no-timer.json"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("the claim 'none generates fast' names no timer"), std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

TEST(SuiteCli, SigintStopsARunningSuiteWithRowsAndAReport) {
  const fs::path dir = temp_dir("cli_sigint");
  const std::string scene = test::source_dir() + "/experiments/scenes/demo.json";
  std::string eps;
  for (int i = 1; i <= 40; ++i) eps += (i > 1 ? ", " : "") + std::to_string(0.01 * i);
  std::ofstream(dir / "slow.json") << R"({"suite": "slow", "repeat": 1, "experiments": [
    {"name": "e", "kind": "shadow", "scene": ")" +
                                          scene + R"(", "strategy": "dsm",
     "params": {"res": 32}, "sweep": {"eps": [)" +
                                          eps + R"(]},
     "settings": {"width": 48, "height": 32, "probe_points": 20, "images": 0}}]})";
  const std::string suite = (dir / "slow.json").string(), out = (dir / "out").string();
  std::vector<std::string> args = {kBinary, "suite", suite, "--out", out, "--backend", "cpu"};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  ASSERT_EQ(posix_spawn(&pid, kBinary.c_str(), nullptr, nullptr, argv.data(), environ), 0);
  // Wait until the first experiment is recorded in the result folder, then press Ctrl-C. The
  // folder is filled under a hidden ".new-HOST-PID.partial" name and renamed into place, so only a
  // progress marker in a visible folder proves the first rows are there.
  fs::path rows;
  for (int i = 0; i < 600 && rows.empty(); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    std::error_code ec;
    for (const auto& e : fs::recursive_directory_iterator(out, ec)) {
      const fs::path folder = e.path().parent_path();
      if (e.path().filename() == "progress.jsonl" && folder.filename().string()[0] != '.' &&
          fs::file_size(e.path(), ec) > 0)
        rows = folder / "rows.csv";
    }
  }
  ASSERT_FALSE(rows.empty()) << "the suite wrote no rows";
  kill(pid, SIGINT);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 130);
  std::ifstream report(rows.parent_path() / "report.md");
  const std::string md((std::istreambuf_iterator<char>(report)), std::istreambuf_iterator<char>());
  EXPECT_NE(md.find("interrupted after "), std::string::npos) << md;
  EXPECT_NE(md.find("of 40 experiments"), std::string::npos) << md;
  EXPECT_EQ(md.find("after 0 of 40"), std::string::npos) << md;
  EXPECT_EQ(md.find("after 40 of 40"), std::string::npos) << md;
}

// DIR/NAME.json: a suite of one shadow experiment on demo.json with `fields` (its strategies
// and settings, each line ending in a comma) and the claim "none generates faster" than dsm.
fs::path claim_suite(const fs::path& dir, const std::string& name, const std::string& fields) {
  const fs::path suite = dir / (name + ".json");
  std::ofstream(suite) << R"({"suite": ")" << name
                       << R"(", "repeat": 2, "experiments": [{"name": "a", "kind": "shadow",
    "scene": ")" << test::source_dir()
                       << R"(/experiments/scenes/demo.json", )" << fields << R"(
    "findings": [{"claim": "none generates faster", "lower": ["strategy=none", "generate_ms"],
                  "than": ["strategy=dsm", "generate_ms"], "timer": "generate_ms"}]}]})";
  return suite;
}

TEST(SuiteCli, RunsMakesIndependentProcessRunsPooledInOneReport) {
  const fs::path dir = temp_dir("cli_runs");
  const fs::path suite =
      claim_suite(dir, "runs", R"("strategy": ["none", {"name": "dsm", "params": {"res": 16}}],
    "settings": {"width": 16, "height": 12, "probe_points": 10, "images": 0},)");
  const std::string out = (dir / "out").string();
  const CommandResult r = run("suite " + suite.string() + " --backend cpu --runs 3 --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("run 3 of 3"), std::string::npos) << r.output;
  const size_t at = r.output.find("report: ");
  ASSERT_NE(at, std::string::npos) << r.output;
  const std::string report =
      r.output.substr(at + 8, r.output.find('\n', at) - at - 8);  // FOLDER/report.md
  const fs::path folder = fs::path(report).parent_path();
  std::ifstream runs_in(folder / "runs.json");
  std::stringstream runs;
  runs << runs_in.rdbuf();
  EXPECT_EQ(nlohmann::json::parse(runs.str())["runs"].size(), 2u) << runs.str();
  std::ifstream md_in(report);
  std::stringstream md;
  md << md_in.rdbuf();
  EXPECT_NE(md.str().find("rest on 3 independent process runs"), std::string::npos) << md.str();
  EXPECT_NE(md.str().find("3 runs x 2 repetitions, 1 vs 1 items"), std::string::npos) << md.str();
  // Rounds are whole suites in fresh processes: no shards, workers or resume.
  const CommandResult sharded =
      run("suite " + suite.string() + " --backend cpu --runs 3 --shard 1/2 --out " + out);
  EXPECT_EQ(sharded.exit_code, 2) << sharded.output;
  EXPECT_NE(sharded.output.find("--runs"), std::string::npos) << sharded.output;
}

// --protocol replicate on a CPU smoke suite: 5 rounds, each with its items permuted by its own
// recorded seed (--order-seed 100: 100 .. 104) and the claim's sides in adjacent pairs; the
// report says so and pools the 5 runs.
TEST(SuiteCli, ReplicateProtocolPermutesEachRunWithARecordedSeed) {
  const fs::path dir = temp_dir("cli_replicate");
  const fs::path suite = claim_suite(
      dir, "replicate",
      R"("strategy": ["none", {"name": "dsm", "params": {"res": 16}}, {"name": "dsm", "params": {"res": 32}}],
    "settings": {"width": 64, "height": 48, "probe_points": 10, "images": 0},
    "smoke": {"settings": {"width": 16, "height": 12}},
    "aa_duplicates": true,)");
  const std::string out = (dir / "out").string();
  const CommandResult r =
      run("suite " + suite.string() +
          " --backend cpu --smoke --protocol replicate --order-seed 100 --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("run 5 of 5"), std::string::npos) << r.output;
  const size_t at = r.output.find("report: ");
  ASSERT_NE(at, std::string::npos) << r.output;
  const fs::path report = r.output.substr(at + 8, r.output.find('\n', at) - at - 8);
  const fs::path folder = report.parent_path();
  EXPECT_NE(folder.string().find("5runs-replicate"), std::string::npos) << folder;
  std::vector<fs::path> folders{folder};
  std::ifstream runs_in(folder / "runs.json");
  const nlohmann::json runs = nlohmann::json::parse(runs_in);
  for (const auto& other : runs["runs"]) folders.push_back(folder / other.get<std::string>());
  ASSERT_EQ(folders.size(), 5u);
  std::set<nlohmann::json> orders;
  for (size_t k = 0; k < folders.size(); ++k) {
    std::ifstream meta_in(folders[k] / "meta.json");
    const nlohmann::json meta = nlohmann::json::parse(meta_in);
    EXPECT_EQ(meta["order"]["protocol"], "replicate");
    EXPECT_EQ(meta["order"]["seed"].get<uint64_t>(), 100 + k);
    EXPECT_EQ(meta["planned_items"].size(), 6u);  // 3 configurations and their A/A copies
    orders.insert(meta["planned_items"]);
  }
  EXPECT_GT(orders.size(), 1u);  // the runs' orders differ
  std::ifstream md_in(report);
  std::stringstream md;
  md << md_in.rdbuf();
  EXPECT_NE(md.str().find("- item order: replicate protocol in 5 of 5 runs: each run's items "
                          "permuted with its own seed (100, 101, 102, 103, 104"),
            std::string::npos)
      << md.str();
  EXPECT_NE(md.str().find("5 runs x 2 repetitions, 2 vs 4 items"), std::string::npos) << md.str();
  EXPECT_NE(md.str().find("- A/A false-positive rate: "), std::string::npos) << md.str();
  EXPECT_NE(md.str().find("3 pairs, 5 runs"), std::string::npos) << md.str();
  // Fewer than 5 runs is not the protocol.
  const CommandResult short_run =
      run("suite " + suite.string() +
          " --backend cpu --smoke --protocol replicate --runs 3 --out " + out);
  EXPECT_EQ(short_run.exit_code, 2) << short_run.output;
  EXPECT_NE(short_run.output.find("--protocol replicate"), std::string::npos) << short_run.output;
}

}  // namespace
}  // namespace dv
