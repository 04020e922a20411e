// What the tests of killed and resumed suite runs share: a small resumable CPU suite, the real
// `deepvox` started as a child and killed with SIGKILL, what a kill leaves in a folder
// (simulate_kill), the result folders of a run and their rows without timings, and a fixture
// that runs and resumes the suite in process.
#pragma once

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "core/json_reader.h"
#include "experiments/harness/rows.h"
#include "experiments/harness/runner.h"
#include "experiments/source_paths.h"
#include "tests/experiments/harness_test.h"

extern char** environ;

namespace dv::test {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

inline const std::string kBinary = binary_dir() + "/bin/deepvox";

// A small CPU suite: ten DSM items that write PNGs (the reference once, render and difference
// per item) and two voxelizer items.
inline std::string small_suite() {
  const std::string scene = source_dir() + "/experiments/scenes/demo.json";
  std::string eps;
  for (int i = 1; i <= 10; ++i) eps += (i > 1 ? ", " : "") + std::to_string(0.02 * i);
  return R"({"suite": "resumable", "repeat": 1, "experiments": [
    {"name": "dsm", "kind": "shadow", "scene": ")" +
         scene + R"(", "strategy": "dsm", "params": {"res": 32}, "sweep": {"eps": [)" + eps +
         R"(]},
     "settings": {"width": 40, "height": 30, "probe_points": 20, "seed": 5, "images": 1}},
    {"name": "voxels", "kind": "voxelize", "scene": ")" +
         scene + R"(", "strategy": ["exact", "sat"], "settings": {"res": "32"}}]})";
}

inline std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

inline std::vector<std::string> untimed_rows_file(const fs::path& folder) {
  return untimed(read_rows_csv((folder / "rows.csv").string()));
}

// Each (item, metric, stat) once in rows.csv, and each item once in progress.jsonl.
inline void expect_no_duplicates(const fs::path& folder) {
  std::set<std::string> seen;
  for (const Row& r : read_rows_csv((folder / "rows.csv").string()))
    EXPECT_TRUE(seen.insert(std::to_string(r.item) + "|" + r.metric + "|" + r.stat).second)
        << "duplicate row: item " << r.item << " " << r.metric << ":" << r.stat;
  std::set<int> items;
  std::istringstream progress(read(folder / "progress.jsonl"));
  for (std::string line; std::getline(progress, line);)
    EXPECT_TRUE(items.insert(Json::parse(line)["item"].get<int>()).second) << line;
}

// The result folders (with meta.json) under OUT/<suite>/, not the hidden one a new run fills.
inline std::vector<fs::path> result_folders(const fs::path& root) {
  std::vector<fs::path> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(root, ec))
    if (fs::is_regular_file(e.path() / "meta.json") &&
        e.path().filename().string().rfind('.', 0) != 0)  // not a new folder being filled
      out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

// `deepvox ARGS...` started with its output in `log`; with `own_group` in a process group of its
// own (so that a test can kill it with its workers).
inline pid_t spawn(std::vector<std::string> args, const fs::path& log, bool own_group = false) {
  args.insert(args.begin(), kBinary);
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_addopen(&files, 1, log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
  posix_spawn_file_actions_adddup2(&files, 1, 2);
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  if (own_group) {
    posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP);
    posix_spawnattr_setpgroup(&attr, 0);
  }
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, kBinary.c_str(), &files, &attr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&files);
  posix_spawnattr_destroy(&attr);
  EXPECT_EQ(rc, 0) << "cannot start " << kBinary;
  return pid;
}

// Waits for `pid` at most `delay`; kills it with SIGKILL when it still runs then. Returns true
// when it was killed, false when it had ended (its exit code in `exit_code`).
inline bool kill_after(pid_t pid, std::chrono::milliseconds delay, int& exit_code) {
  const auto until = Clock::now() + delay;
  int status = 0;
  while (Clock::now() < until) {
    if (waitpid(pid, &status, WNOHANG) == pid) {
      exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      return false;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  kill(pid, SIGKILL);  // still our unreaped child: the pid cannot have been reused
  waitpid(pid, &status, 0);
  exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL;
}

class Resume : public HarnessTest {
 protected:
  void SetUp() override {
    HarnessTest::SetUp();
    suite_ = write("resumable.json", small_suite());
  }
  SuiteOutcome run(const std::string& out, const std::string& shard = "") {
    SuiteOptions o = cpu_options(suite_);
    o.out = (dir_ / out).string();
    o.shard = shard;
    o.costs = "estimate";
    o.report = false;
    return run_suite(o);
  }
  SuiteOutcome resume(const std::string& folder, bool force = false) {
    SuiteOptions o = cpu_options(suite_);
    o.resume = true;
    o.resume_dir = folder;
    o.force = force;
    return run_suite(o);
  }
  std::string suite_;
};

// What a kill leaves when it lands after the rows of the items from `keep` on were appended but
// before their markers: progress.jsonl keeps `keep` whole lines and half of the next, rows.csv
// keeps every row plus half a row, meta.json says running, params.json and report.md are gone.
inline void simulate_kill(const fs::path& folder, int keep) {
  std::istringstream progress(read(folder / "progress.jsonl"));
  std::string kept, line;
  for (int i = 0; i < keep && std::getline(progress, line); ++i) kept += line + "\n";
  if (std::getline(progress, line)) kept += line.substr(0, line.size() / 2);
  std::ofstream(folder / "progress.jsonl", std::ios::trunc) << kept;
  std::ofstream(folder / "rows.csv", std::ios::app) << "resumable,99,dsm,shadow,\"half a ro";
  Json meta = parse_json_file((folder / "meta.json").string());
  meta["state"] = "running";
  for (const char* key : {"done", "failed", "skipped", "interrupted", "elapsed_s"}) meta.erase(key);
  std::ofstream(folder / "meta.json", std::ios::trunc) << meta.dump(1);
  fs::remove(folder / "params.json");
  fs::remove(folder / "report.md");
}

}  // namespace dv::test
