// Suites that survive being killed: the real `deepvox suite` killed with SIGKILL at
// seeded random instants and resumed each time ends with the rows of one uninterrupted run (no
// duplicate, timings aside), and `deepvox report` reads every partial folder; a torn row group
// is ignored and cut off; resuming with another suite file or commit is refused unless forced
// (then the report says the run is mixed); merge takes resumed shards and names unfinished
// ones; an out-of-memory experiment fails its row with the bytes asked for while the suite goes
// on; a full disk (a small tmpfs) stops the run with a clear error, its own exit code (4) and a
// folder that resumes; RunJournal::open_or_resume, the one door all of it goes through, on its
// own (a new folder, the newest unfinished run found, each refusal before the folder is
// touched) and removing a killed run's hidden filling folder. What the tests share is in
// resume_support.h; resumed --gpus and SLURM sessions and the folder's lock file are tested in
// test_long_runs.cpp.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/mount.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <thread>

#include "core/error.h"
#include "core/json_reader.h"
#include "experiments/harness/durable_file.h"
#include "experiments/harness/merge.h"
#include "experiments/harness/report.h"
#include "experiments/harness/rows.h"
#include "experiments/harness/run_journal.h"
#include "experiments/harness/runner.h"
#include "experiments/source_paths.h"
#include "tests/apps/deepvox/cli_run.h"
#include "tests/experiments/harness_test.h"
#include "tests/experiments/resume_support.h"

namespace dv {
namespace {

using namespace test;

TEST_F(Resume, KilledAtRandomInstantsResumesToTheRowsOfOneRun) {
  const fs::path log = dir_ / "runs.log";
  const auto started = Clock::now();
  int exit_code = -1;
  const pid_t reference_pid =
      spawn({"suite", suite_, "--backend", "cpu", "--out", (dir_ / "reference").string()}, log);
  kill_after(reference_pid, std::chrono::minutes(5), exit_code);
  ASSERT_EQ(exit_code, 0) << read(log);
  double run_ms = std::chrono::duration<double, std::milli>(Clock::now() - started).count();
  const std::vector<fs::path> reference = result_folders(dir_ / "reference" / "resumable");
  ASSERT_EQ(reference.size(), 1u);
  const int total = parse_json_file((reference[0] / "meta.json").string())["items"].get<int>();

  const char* seed_text = std::getenv("DEEPVOX_KILL_SEED");
  const unsigned seed = seed_text ? unsigned(std::strtoul(seed_text, nullptr, 10)) : 42u;
  std::mt19937 random(seed);
  std::cout << "SIGKILL seed " << seed << " (DEEPVOX_KILL_SEED), uninterrupted run " << run_ms
            << " ms\n";
  const fs::path out = dir_ / "out", root = out / "resumable";
  constexpr int kKills = 10, kRestarts = 2;
  int hits = 0, attempts = 0, partial_reports = 0, kills_tried = 0, restarts = 0;
  bool finished = false;
  for (; !finished && attempts < (kKills + 5) * (kRestarts + 1); ++attempts) {
    // Resume the folder when one exists (the first kill may land before it does).
    // A kill that lands after the last row but before the process ends leaves a finished
    // folder, which `--resume` alone does not look for (it finds unfinished runs): it is named
    // then, as a user would, so that its report is written.
    const bool resuming = !result_folders(root).empty();
    std::vector<std::string> args = {"suite", suite_, "--backend", "cpu", "--out", out.string()};
    int missing = total;
    if (resuming) {
      const RunState state = read_run_state(result_folders(root).back());
      missing = int(state.missing.size());
      args.push_back("--resume");
      if (state.finished) args.push_back(result_folders(root).back().string());
    }
    // A delay spread over most of what this attempt has left to do (an item's share of the
    // run for start-up), so that the kill lands while it runs; after kKills kills the run goes
    // to its end.
    const double span_ms = 0.7 * run_ms * (missing + 1) / (total + 1);
    std::uniform_real_distribution<double> uniform(0.0, span_ms);
    const auto delay = kills_tried < kKills ? std::chrono::milliseconds(int(uniform(random)))
                                            : std::chrono::milliseconds(std::chrono::minutes(5));
    const auto spawned = Clock::now();
    const pid_t pid = spawn(args, log);
    const bool killed = kill_after(pid, delay, exit_code);
    std::cout << "attempt " << attempts + 1 << (resuming ? " (--resume)" : "") << ": "
              << (killed ? "killed after " + std::to_string(delay.count()) + " ms"
                         : "exit " + std::to_string(exit_code))
              << "\n";
    if (!killed) {
      ASSERT_EQ(exit_code, 0) << read(log);
      if (kills_tried < kKills && restarts < kRestarts) {
        // The run ended before its kill: it ran faster than the uninterrupted run measured (a
        // machine busy with other tests then), so the delays overshot. Start again from no
        // folder, with this run's time.
        run_ms = std::min(
            run_ms, std::chrono::duration<double, std::milli>(Clock::now() - spawned).count());
        fs::remove_all(out);
        hits = partial_reports = kills_tried = 0;
        ++restarts;
        std::cout << "restart " << restarts << " with an uninterrupted run of " << run_ms
                  << " ms\n";
        continue;
      }
      finished = true;
      break;
    }
    ++hits;
    ++kills_tried;
    const std::vector<fs::path> folders = result_folders(root);
    if (folders.empty()) continue;  // killed before its folder existed
    ASSERT_EQ(folders.size(), 1u) << "a resumed run made a second folder";
    // The partial folder is reportable and says what is missing.
    const CommandResult report = dv::run("report " + folders[0].string());
    ASSERT_EQ(report.exit_code, 0) << report.output;
    const RunState state = read_run_state(folders[0]);
    if (!state.missing.empty()) {
      const std::string md = read(folders[0] / "report.md");
      EXPECT_NE(md.find("PARTIAL: " + std::to_string(state.done) + " of " + std::to_string(total) +
                        " experiments complete"),
                std::string::npos)
          << md;
      EXPECT_NE(md.find("- item " + std::to_string(state.missing.front()) + ": "),
                std::string::npos)
          << md;
      ++partial_reports;
    }
  }
  ASSERT_TRUE(finished) << "the run did not finish after " << attempts << " attempts";
  std::cout << hits << " kills landed in " << attempts + 1 << " attempts, " << partial_reports
            << " partial folders reported\n";
  EXPECT_GE(hits, 3) << "too few kills landed while the suite ran";
  const std::vector<fs::path> folders = result_folders(root);
  ASSERT_EQ(folders.size(), 1u);
  const RunState state = read_run_state(folders[0]);
  EXPECT_TRUE(state.finished);
  EXPECT_EQ(state.done, total);
  EXPECT_EQ(untimed_rows_file(folders[0]), untimed_rows_file(reference[0]));
  expect_no_duplicates(folders[0]);
  EXPECT_EQ(parse_json_file((folders[0] / "params.json").string()).size(), size_t(total));
  const std::string md = read(folders[0] / "report.md");
  EXPECT_NE(md.find("ran " + std::to_string(total) + " of " + std::to_string(total)),
            std::string::npos)
      << md;
}

TEST_F(Resume, TornRowGroupIsIgnoredReportedAndRunAgain) {
  const SuiteOutcome whole = run("out");
  ASSERT_EQ(whole.exit_code, 0);
  const std::vector<std::string> expected = untimed_rows_file(whole.folder);
  simulate_kill(whole.folder, 4);
  const RunState state = read_run_state(whole.folder);
  EXPECT_FALSE(state.finished);
  EXPECT_EQ(state.done, 4);
  EXPECT_EQ(state.missing, (std::vector<int>{4, 5, 6, 7, 8, 9, 10, 11}));
  for (const Row& r : state.rows) EXPECT_LT(r.item, 4) << "a row of an unfinished group was read";
  build_report(whole.folder);
  const std::string md = read(fs::path(whole.folder) / "report.md");
  EXPECT_NE(md.find("PARTIAL: 4 of 12 experiments complete, 8 missing (the run was killed"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("- item 11: voxels: sat on "), std::string::npos) << md;
  EXPECT_NE(md.find("--resume " + whole.folder), std::string::npos) << md;
  // The newest unfinished run is found without naming it; only the missing items run.
  SuiteOptions o = cpu_options(suite_);
  o.resume = true;
  o.report = false;
  const SuiteOutcome resumed = run_suite(o);
  EXPECT_EQ(resumed.folder, whole.folder);
  EXPECT_EQ(resumed.ran_now, 8);
  EXPECT_EQ(resumed.done, 12);
  EXPECT_EQ(resumed.exit_code, 0);
  EXPECT_EQ(untimed_rows_file(whole.folder), expected);
  expect_no_duplicates(whole.folder);
  const Json meta = parse_json_file(whole.folder + "/meta.json");
  EXPECT_EQ(meta["state"], "finished");
  EXPECT_EQ(meta["attempts"].size(), 2u);
  // A finished folder has nothing to resume; --resume without a folder then finds none.
  EXPECT_EQ(resume(whole.folder).ran_now, 0);
  try {
    run_suite(o);
    ADD_FAILURE() << "resumed a finished run";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no unfinished run of suite 'resumable'"),
              std::string::npos)
        << e.what();
  }
}

TEST_F(Resume, AnotherSuiteFileOrCommitIsRefusedUnlessForced) {
  const SuiteOutcome first = run("out");
  simulate_kill(first.folder, 3);
  std::ofstream(suite_, std::ios::app) << "\n";  // same experiments, another file hash
  try {
    resume(first.folder);
    ADD_FAILURE() << "resumed with another suite file";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(first.folder + ": cannot resume: the suite file differs"), std::string::npos)
        << m;
    EXPECT_NE(m.find("--force"), std::string::npos) << m;
  }
  EXPECT_FALSE(read_run_state(first.folder).finished) << "a refused resume changed the folder";
  Json meta = parse_json_file(first.folder + "/meta.json");
  meta["run"]["git_sha"] = "0123456789ab";
  std::ofstream(first.folder + "/meta.json", std::ios::trunc) << meta.dump(1);
  try {
    resume(first.folder);
    ADD_FAILURE() << "resumed with another commit";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("the commit differs (the folder ran 0123456789ab"),
              std::string::npos)
        << e.what();
  }
  // The CLI: exit 2, the folder named.
  const CommandResult cli = dv::run("suite " + suite_ + " --resume " + first.folder);
  EXPECT_EQ(cli.exit_code, 2) << cli.output;
  EXPECT_NE(cli.output.find(first.folder), std::string::npos) << cli.output;
  const SuiteOutcome forced = resume(first.folder, true);
  EXPECT_EQ(forced.exit_code, 0);
  EXPECT_EQ(forced.ran_now, 9);
  meta = parse_json_file(first.folder + "/meta.json");
  EXPECT_EQ(meta["mixed"], true);
  EXPECT_EQ(meta["attempts"][1]["forced"], Json::array({"suite file", "commit"}));
  const std::string md = read(fs::path(first.folder) / "report.md");
  EXPECT_NE(md.find("- MIXED (--resume --force): items 3, 4, 5, 6, 7, 8, 9, 10, 11 ran with "
                    "another suite file and commit"),
            std::string::npos)
      << md;
  // Options that differ from the folder's are refused too.
  simulate_kill(first.folder, 11);
  SuiteOptions o = cpu_options(suite_);
  o.resume = true;
  o.resume_dir = first.folder;
  o.repeat = 2;
  o.force = true;
  try {
    run_suite(o);
    ADD_FAILURE() << "resumed with another --repeat";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("ran with --repeat 1"), std::string::npos) << e.what();
  }
}

TEST_F(Resume, MergeTakesResumedShardsAndNamesUnfinishedOnes) {
  const SuiteOutcome whole = run("whole");
  const SuiteOutcome first = run("out", "1/2");
  const SuiteOutcome second = run("out", "2/2");
  simulate_kill(second.folder, 2);
  try {
    merge_shards({first.folder, second.folder}, "");
    ADD_FAILURE() << "an unfinished shard merged";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("shard 2 is unfinished: 2 of " +
                                         std::to_string(second.total) + " experiments complete"),
              std::string::npos)
        << e.what();
  }
  const RunState killed = read_run_state(second.folder);
  const std::string partial = merge_shards({first.folder, second.folder}, "", true);
  const Json meta = parse_json_file(partial + "/meta.json");
  EXPECT_EQ(meta["partial_shards"], Json::array({2}));
  EXPECT_EQ(meta["missing_items"].size(), killed.missing.size());
  EXPECT_EQ(meta["done"], whole.done - int(killed.missing.size()));
  const std::string md = read(fs::path(partial) / "report.md");
  EXPECT_NE(md.find("- item " + std::to_string(killed.missing.front()) + ": "), std::string::npos)
      << md;
  EXPECT_NE(md.find("PARTIAL: " + std::to_string(killed.missing.size()) + " planned"),
            std::string::npos)
      << md;
  SuiteOptions o = cpu_options(suite_);
  o.out = (dir_ / "out").string();
  o.shard = "2/2";
  o.resume = true;
  o.report = false;
  EXPECT_EQ(run_suite(o).folder, second.folder);
  const std::string merged = merge_shards({second.folder, first.folder}, "");
  EXPECT_EQ(untimed_rows_file(merged), untimed_rows_file(whole.folder));
}

// A strategy asking for more memory than DEEPVOX_MEMORY_LIMIT allows: the reservation check
// that guards every DSM storage buffer on the host and the device (cuda/memory_check.h) throws
// the OutOfMemory that a failed device allocation throws too.
TEST_F(Resume, OutOfMemoryFailsOneRowWithTheBytesAndTheSuiteGoesOn) {
  const std::string scene = test::source_dir() + "/experiments/scenes/demo.json";
  const std::string suite = write("oom.json", R"({"suite": "oom", "repeat": 1, "experiments": [
    {"name": "e", "kind": "shadow", "scene": ")" + scene +
                                                  R"(", "strategy": "dsm",
     "params": {"storage": "texture3d", "storage.sizing": "thesis"}, "sweep": {"res": [16, 256, 32]},
     "settings": {"width": 40, "height": 30, "probe_points": 20, "images": 0}}]})");
  setenv("DEEPVOX_MEMORY_LIMIT", "20000000", 1);
  const CommandResult r =
      dv::run("suite " + suite + " --backend cpu --out " + (dir_ / "out").string());
  unsetenv("DEEPVOX_MEMORY_LIMIT");
  ASSERT_EQ(r.exit_code, 3) << r.output;  // some failed
  EXPECT_NE(r.output.find("out of memory: dsm texture3d atlas"), std::string::npos) << r.output;
  const std::vector<fs::path> folders = result_folders(dir_ / "out" / "oom");
  ASSERT_EQ(folders.size(), 1u);
  const std::vector<Row> rows = read_rows_csv((folders[0] / "rows.csv").string());
  std::map<int, std::map<std::string, const Row*>> by_item;
  for (const Row& row : rows) by_item[row.item][row.metric + ":" + row.stat] = &row;
  ASSERT_TRUE(by_item[1].count("failed:value"));
  ASSERT_TRUE(by_item[1].count("out_of_memory:bytes_asked"));
  const double asked = by_item[1]["out_of_memory:bytes_asked"]->value;
  EXPECT_GT(asked, 20e6);
  EXPECT_EQ(by_item[1]["out_of_memory:bytes_asked"]->unit, "bytes");
  EXPECT_NE(by_item[1]["failed:value"]->note.find(std::to_string(int64_t(asked)) + " bytes) asked"),
            std::string::npos)
      << by_item[1]["failed:value"]->note;
  for (int item : {0, 2}) {
    EXPECT_FALSE(by_item[item].count("failed:value")) << "item " << item;
    EXPECT_TRUE(by_item[item].count("bytes:value")) << "item " << item << " did not run";
  }
  const std::string md = read(folders[0] / "report.md");
  EXPECT_NE(md.find("failed: out of memory: dsm texture3d atlas"), std::string::npos) << md;
}

// A tmpfs mounted for the test and unmounted at its end.
struct Tmpfs {
  fs::path at;
  bool mounted = false;
  std::string why_not;
  Tmpfs(const fs::path& where, const std::string& size) : at(where) {
    fs::create_directories(at);
    mounted = mount("tmpfs", at.c_str(), "tmpfs", 0, ("size=" + size).c_str()) == 0;
    if (!mounted) why_not = std::strerror(errno);
  }
  bool resize(const std::string& size) const {
    return mount("tmpfs", at.c_str(), "tmpfs", MS_REMOUNT, ("size=" + size).c_str()) == 0;
  }
  ~Tmpfs() {
    if (mounted) umount2(at.c_str(), MNT_DETACH);
  }
};

TEST_F(Resume, FullDiskStopsTheRunAndTheFolderResumesAfterSpaceIsFreed) {
  const SuiteOutcome reference = run("reference");
  // Room for the folder's first files and a few items, not for all twelve.
  const Tmpfs disk(dir_ / "disk", "80k");
  if (!disk.mounted)
    GTEST_SKIP() << "cannot mount a tmpfs here (" << disk.why_not
                 << "; needs root with CAP_SYS_ADMIN): the full-disk case is not tested";
  const CommandResult full =
      dv::run("suite " + suite_ + " --backend cpu --costs estimate --out " + disk.at.string());
  EXPECT_EQ(full.exit_code, kSuiteStopped) << full.output;  // its own code, not an error's 1
  EXPECT_NE(full.output.find("No space left on device"), std::string::npos) << full.output;
  EXPECT_NE(full.output.find("the run stopped; "), std::string::npos) << full.output;
  const std::vector<fs::path> folders = result_folders(disk.at / "resumable");
  ASSERT_EQ(folders.size(), 1u) << full.output;
  EXPECT_NE(full.output.find("--resume " + folders[0].string()), std::string::npos) << full.output;
  const RunState stopped = read_run_state(folders[0]);
  EXPECT_FALSE(stopped.missing.empty()) << "the disk did not fill: make the tmpfs smaller";
  EXPECT_GT(stopped.done, 0) << "nothing fit: make the tmpfs larger";
  ASSERT_TRUE(disk.resize("64m")) << std::strerror(errno);
  const CommandResult report = dv::run("report " + folders[0].string());
  EXPECT_EQ(report.exit_code, 0) << report.output;
  EXPECT_NE(read(folders[0] / "report.md").find("PARTIAL: " + std::to_string(stopped.done)),
            std::string::npos);
  const CommandResult resumed = dv::run("suite " + suite_ + " --resume --out " + disk.at.string());
  EXPECT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_EQ(untimed_rows_file(folders[0]), untimed_rows_file(reference.folder));
  expect_no_duplicates(folders[0]);
  for (const auto& e : fs::recursive_directory_iterator(folders[0]))
    EXPECT_NE(e.path().extension(), ".tmp") << "temporary file left: " << e.path();
}

class OpenOrResume : public HarnessTest {
 protected:
  JournalRequest request() const {
    JournalRequest r;
    r.out = dir_ / "out";
    r.suite = "tiny";
    r.suite_file = (dir_ / "tiny.json").string();
    r.suite_hash = "00000000000000aa";
    r.git_sha = "0123456789ab";
    return r;
  }
};

TEST_F(OpenOrResume, CreatesThenFindsChecksAndReopensTheUnfinishedRun) {
  JournalRequest r = request();
  EXPECT_THROW(RunJournal::open_or_resume([&] {
                 JournalRequest none = r;
                 none.resume = true;
                 return none;
               }()),
               InputError);  // nothing to resume yet
  r.meta = {{"suite", "tiny"},
            {"suite_file", r.suite_file},
            {"suite_hash", r.suite_hash},
            {"repeat", 1},
            {"only", ""},
            {"smoke", false},
            {"shard", {{"index", 1}, {"count", 1}}},
            {"planned_items", {0, 1}},
            {"state", "running"},
            {"run", {{"git_sha", r.git_sha}, {"backend", "cpu"}}}};
  r.suite_text = "{}";
  r.command = "deepvox suite tiny";
  OpenedRun created = RunJournal::open_or_resume(r);
  const fs::path folder = created.journal.dir();
  EXPECT_EQ(folder.parent_path(), dir_ / "out" / "tiny");
  EXPECT_TRUE(created.forced.empty());
  created.journal.close();
  const std::string meta_before = read(folder / "meta.json");

  JournalRequest resume = request();
  resume.resume = true;  // no folder given: the newest unfinished run of suite tiny
  const auto refused = [&](JournalRequest bad) {
    try {
      RunJournal::open_or_resume(bad);
    } catch (const InputError& e) {
      EXPECT_EQ(read(folder / "meta.json"), meta_before) << "a refused resume changed the folder";
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  JournalRequest other_commit = resume;
  other_commit.git_sha = "fedcba987654";
  EXPECT_NE(refused(other_commit).find("cannot resume: the commit differs"), std::string::npos);
  JournalRequest other_repeat = resume;
  other_repeat.given.push_back(
      {"--repeat", 3, [](const Json& meta) -> Json { return meta["repeat"]; }});
  EXPECT_NE(refused(other_repeat).find("--repeat 3: " + folder.string() + " ran with --repeat 1"),
            std::string::npos);
  JournalRequest other_shard = resume;
  other_shard.shard_count = 2;
  EXPECT_NE(refused(other_shard).find("no unfinished run of suite 'tiny' shard 1/2"),
            std::string::npos);

  JournalRequest forced = other_commit;
  forced.force = true;
  forced.given.push_back({"--repeat", 1, [](const Json& meta) -> Json { return meta["repeat"]; }});
  OpenedRun reopened = RunJournal::open_or_resume(forced);
  EXPECT_EQ(reopened.journal.dir(), folder);
  EXPECT_EQ(reopened.forced, std::vector<std::string>{"commit"});
  EXPECT_EQ(reopened.before.missing, (std::vector<int>{0, 1}));
  reopened.journal.close();
}

// A run killed while it filled its new folder leaves the hidden filling folder behind; the next
// run on this host removes it when its process is gone, and leaves a live process's (this test's
// parent) and another host's alone.
TEST_F(OpenOrResume, NewRunRemovesTheFillingFolderOfAKilledProcess) {
  const fs::path parent = dir_ / "out" / "tiny";
  fs::create_directories(parent);
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) _exit(0);
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);  // reaped: its pid names no process now
  const fs::path killed = parent / filling_folder_name(this_host(), long(child));
  const fs::path alive = parent / filling_folder_name(this_host(), long(getppid()));
  const fs::path elsewhere = parent / filling_folder_name(this_host() + "-other", long(child));
  for (const fs::path& f : {killed, alive, elsewhere}) {
    fs::create_directories(f);
    std::ofstream(f / "meta.json") << "{}";
  }
  JournalRequest r = request();
  r.meta = {{"suite", "tiny"}, {"state", "running"}, {"planned_items", {0}}};
  r.suite_text = "{}";
  r.command = "deepvox suite tiny";
  OpenedRun created = RunJournal::open_or_resume(r);
  created.journal.close();
  EXPECT_FALSE(fs::exists(killed));
  EXPECT_TRUE(fs::exists(alive));
  EXPECT_TRUE(fs::exists(elsewhere));
  int visible = 0;
  for (const auto& e : fs::directory_iterator(parent))
    visible += e.path().filename().string()[0] != '.';
  EXPECT_EQ(visible, 1);  // the new run's folder
}

}  // namespace
}  // namespace dv
