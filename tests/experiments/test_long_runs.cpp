// Long runs on shared machines: a `--gpus` session killed as a whole resumes (each worker its
// shard) to the rows of one run; a worker killed alone is started again on its shard instead of
// a partial merge; a SLURM session is handed to sbatch again with its own scripts and its tasks
// resume; merge refuses a shard that a live process writes (flock or writer.lock); writer.lock
// keeps one writer where flock fails (flock replaced by one that fails, through LD_PRELOAD) and
// is taken over when stale (a dead pid, another host's old heartbeat, a requeued SLURM job); on
// CUDA a DSM whose maps cannot fit the card fails its row with the bytes and the next rows run.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "core/error.h"
#include "core/json_reader.h"
#include "cuda/device_memory.h"
#include "cuda/memory_check.h"
#include "experiments/harness/merge.h"
#include "experiments/harness/rows.h"
#include "experiments/harness/run_journal.h"
#include "experiments/harness/run_metadata.h"
#include "experiments/harness/runner.h"
#include "experiments/harness/writer_lock.h"
#include "experiments/source_paths.h"
#include "tests/apps/deepvox/cli_run.h"
#include "tests/experiments/resume_support.h"

namespace dv {
namespace {

using namespace test;

// The folders of a --gpus session under OUT/<suite>/: the session (-Nworkers) and the merged
// ones.
fs::path session_folder(const fs::path& root) {
  for (const auto& e : fs::directory_iterator(root))
    if (e.path().string().find("workers") != std::string::npos) return e.path();
  return {};
}
std::vector<fs::path> merged_folders(const fs::path& root) {
  std::vector<fs::path> out;
  for (const fs::path& f : result_folders(root))
    if (f.string().find("-merged") != std::string::npos) out.push_back(f);
  return out;
}

// Complete items in a folder's progress.jsonl (0 when it has none yet).
int markers(const fs::path& folder) {
  std::istringstream progress(read(folder / "progress.jsonl"));
  int n = 0;
  for (std::string line; std::getline(progress, line);) n += !line.empty();
  return n;
}

int wait_exit(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// Polls until `ready` holds (true) or 5 minutes passed (false).
template <class Ready>
bool wait_for(Ready ready) {
  const auto until = Clock::now() + std::chrono::minutes(5);
  while (Clock::now() < until) {
    if (ready()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return false;
}

// The journaled shard folders of a session, shard k at [k - 1] (empty path: none yet).
std::vector<fs::path> shard_folders(const fs::path& session, const std::string& suite, int count) {
  std::vector<fs::path> out;
  for (int k = 1; k <= count; ++k)
    out.push_back(newest_run(session / "shards", suite, k, count, false));
  return out;
}

class LongRuns : public Resume {};

TEST_F(LongRuns, GpusSessionKilledWholeResumesEachShardToTheRowsOfOneRun) {
  const SuiteOutcome plain = run("plain");
  const fs::path out = dir_ / "out", root = out / "resumable", log = dir_ / "gpus.log";
  const pid_t parent = spawn({"suite", suite_, "--backend", "cpu", "--gpus", "2", "--costs",
                              "estimate", "--out", out.string()},
                             log, /*own_group=*/true);
  // Killed, parent and workers at once (a node that went down), once a shard has a complete
  // experiment.
  fs::path session;
  ASSERT_TRUE(wait_for([&] {
    if (session.empty() && fs::is_directory(root)) session = session_folder(root);
    if (session.empty()) return false;
    for (const fs::path& f : shard_folders(session, "resumable", 2))
      if (!f.empty() && markers(f) > 0) return true;
    return false;
  })) << read(log);
  killpg(parent, SIGKILL);
  EXPECT_EQ(wait_exit(parent), 128 + SIGKILL);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));  // the workers are reaped by init
  EXPECT_TRUE(merged_folders(root).empty()) << "a killed session merged";
  int complete = 0;
  for (const fs::path& f : shard_folders(session, "resumable", 2))
    if (!f.empty()) complete += int(read_run_state(f).done);
  EXPECT_LT(complete, 12) << "the session ended before the kill: nothing to resume";

  // Without a folder: the newest unmerged session of the suite with 2 workers.
  const CommandResult resumed = dv::run("suite " + suite_ +
                                        " --backend cpu --gpus 2 --resume "
                                        "--out " +
                                        out.string());
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  const std::vector<fs::path> merged = merged_folders(root);
  ASSERT_EQ(merged.size(), 1u);
  EXPECT_EQ(untimed_rows_file(merged[0]), untimed_rows_file(plain.folder));
  const Json meta = parse_json_file((merged[0] / "meta.json").string());
  EXPECT_FALSE(meta.contains("partial_shards")) << meta.dump(1);
  EXPECT_EQ(meta["done"], 12);
  for (const fs::path& f : shard_folders(session, "resumable", 2)) {
    ASSERT_FALSE(f.empty());
    expect_no_duplicates(f);
    EXPECT_FALSE(fs::exists(f / "writer.lock")) << f;
  }
  // One folder per shard: the resumed workers continued them.
  int shard_dirs = 0;
  for (const auto& e : fs::directory_iterator(session / "shards" / "resumable"))
    shard_dirs += e.is_directory();
  EXPECT_EQ(shard_dirs, 2);
  EXPECT_EQ(parse_json_file((session / "session.json").string())["state"], "merged");
  // Merged: nothing left to resume.
  const CommandResult again = dv::run("suite " + suite_ +
                                      " --backend cpu --gpus 2 --resume "
                                      "--out " +
                                      out.string());
  EXPECT_EQ(again.exit_code, 2) << again.output;
  EXPECT_NE(again.output.find("no unmerged --gpus 2 session of suite 'resumable'"),
            std::string::npos)
      << again.output;
  // Another worker count is refused, naming the session's.
  const CommandResult other = dv::run("suite " + suite_ + " --gpus 3 --resume " + session.string());
  EXPECT_EQ(other.exit_code, 2) << other.output;
  EXPECT_NE(other.output.find("ran 2 workers"), std::string::npos) << other.output;
}

TEST_F(LongRuns, KilledWorkerRestartsOnItsShardInsteadOfAPartialMerge) {
  const SuiteOutcome plain = run("plain");
  const fs::path out = dir_ / "out", root = out / "resumable", log = dir_ / "gpus.log";
  const pid_t parent = spawn({"suite", suite_, "--backend", "cpu", "--gpus", "2", "--costs",
                              "estimate", "--out", out.string()},
                             log, /*own_group=*/true);
  // Shard 1's worker, by the pid its meta.json records, once it completed an experiment.
  fs::path session, shard;
  ASSERT_TRUE(wait_for([&] {
    if (session.empty() && fs::is_directory(root)) session = session_folder(root);
    if (!session.empty() && shard.empty()) shard = shard_folders(session, "resumable", 2)[0];
    return !shard.empty() && markers(shard) > 0;
  })) << read(log);
  const RunState before = read_run_state(shard);
  const pid_t worker = pid_t(before.meta["attempts"][0]["pid"].get<int>());
  const std::string cmdline = read("/proc/" + std::to_string(worker) + "/cmdline");
  if (before.done == int(before.planned.size()) || cmdline.find("1/2") == std::string::npos) {
    wait_exit(parent);
    GTEST_SKIP() << "shard 1 ended before it could be killed (" << before.done << " of "
                 << before.planned.size() << ")";
  }
  ASSERT_EQ(kill(worker, SIGKILL), 0);
  const int code = wait_exit(parent);
  const std::string output = read(log);
  ASSERT_EQ(code, 0) << output;
  EXPECT_NE(output.find("worker 1 ended by signal 9; restarting it to resume its shard (restart "
                        "1 of 3)"),
            std::string::npos)
      << output;
  const std::vector<fs::path> merged = merged_folders(root);
  ASSERT_EQ(merged.size(), 1u);
  EXPECT_EQ(untimed_rows_file(merged[0]), untimed_rows_file(plain.folder));
  EXPECT_FALSE(parse_json_file((merged[0] / "meta.json").string()).contains("partial_shards"));
  const RunState after = read_run_state(shard);
  EXPECT_TRUE(after.finished);
  EXPECT_EQ(after.meta["attempts"].size(), 2u);  // the same folder, resumed
  expect_no_duplicates(shard);
}

TEST_F(LongRuns, SlurmSessionIsSubmittedAgainAndItsTasksResume) {
  const SuiteOutcome plain = run("plain");
  const fs::path out = dir_ / "out";
  const CommandResult wrote = dv::run(
      "suite " + suite_ + " --backend cpu --slurm --gpus 2 --costs estimate --out " + out.string());
  ASSERT_EQ(wrote.exit_code, 0) << wrote.output;
  fs::path session;
  for (const auto& e : fs::directory_iterator(out / "resumable"))
    if (e.path().string().find("-slurm") != std::string::npos) session = e.path();
  ASSERT_FALSE(session.empty()) << wrote.output;
  const std::string array = (session / "slurm" / "array.sbatch").string();
  const std::string merge = (session / "slurm" / "merge.sbatch").string();
  // Both tasks run by hand; shard 2 is then cut back as a kill leaves it (the array job
  // cancelled, or out of time and requeues).
  for (const char* task : {"1", "2"})
    ASSERT_EQ(std::system(("SLURM_ARRAY_TASK_ID=" + std::string(task) + " bash " + array + " > " +
                           (dir_ / "task.log").string() + " 2>&1")
                              .c_str()),
              0)
        << read(dir_ / "task.log");
  const fs::path shard2 = shard_folders(session, "resumable", 2)[1];
  ASSERT_FALSE(shard2.empty());
  simulate_kill(shard2, 1);

  // --resume --submit hands the session's own scripts to sbatch (faked here) again.
  const fs::path bin = dir_ / "bin";
  fs::create_directories(bin);
  std::ofstream(bin / "sbatch") << "#!/bin/sh\necho \"$@\" >> " << (dir_ / "sbatch.log").string()
                                << "\necho $((5000 + $(wc -l < " << (dir_ / "sbatch.log").string()
                                << ")))\n";
  fs::permissions(bin / "sbatch", fs::perms::owner_all);
  const std::string path = bin.string() + ":" + std::getenv("PATH");
  const std::string submit = "PATH=" + path + " " + kBinary + " suite " + suite_ +
                             " --slurm --gpus 2 --resume --submit --out " + out.string() + " > " +
                             (dir_ / "submit.txt").string() + " 2>&1";
  ASSERT_EQ(std::system(submit.c_str()), 0) << read(dir_ / "submit.txt");
  const std::string sbatch = read(dir_ / "sbatch.log");
  EXPECT_EQ(sbatch,
            "--parsable " + array + "\n--parsable --dependency=afterany:5001 " + merge + "\n");
  int sessions = 0;
  for (const auto& e : fs::directory_iterator(out / "resumable"))
    sessions += e.path().string().find("-slurm") != std::string::npos;
  EXPECT_EQ(sessions, 1) << "--resume made another session";
  // Options that differ from the scripts' are refused; so is another task count.
  const CommandResult other =
      dv::run("suite " + suite_ + " --slurm --gpus 3 --resume " + session.string());
  EXPECT_EQ(other.exit_code, 2) << other.output;
  EXPECT_NE(other.output.find("has 2 tasks"), std::string::npos) << other.output;
  const CommandResult partition =
      dv::run("suite " + suite_ + " --slurm --partition big --resume " + session.string());
  EXPECT_EQ(partition.exit_code, 2) << partition.output;

  // What the resubmitted job does: task 2 resumes its folder; the merge equals one run.
  ASSERT_EQ(std::system(("SLURM_ARRAY_TASK_ID=2 bash " + array + " > " +
                         (dir_ / "task.log").string() + " 2>&1")
                            .c_str()),
            0)
      << read(dir_ / "task.log");
  EXPECT_EQ(shard_folders(session, "resumable", 2)[1], shard2);
  EXPECT_EQ(read_run_state(shard2).meta["attempts"].size(), 2u);
  expect_no_duplicates(shard2);
  ASSERT_EQ(
      std::system(("bash " + merge + " > " + (dir_ / "merge.log").string() + " 2>&1").c_str()), 0)
      << read(dir_ / "merge.log");
  const std::vector<fs::path> merged = merged_folders(out / "resumable");
  ASSERT_EQ(merged.size(), 1u);
  EXPECT_EQ(untimed_rows_file(merged[0]), untimed_rows_file(plain.folder));
}

TEST_F(LongRuns, MergeRefusesAShardThatALiveProcessWrites) {
  const SuiteOutcome first = run("out", "1/2");
  const SuiteOutcome second = run("out", "2/2");
  simulate_kill(second.folder, 1);
  const auto expect_refused = [&](bool allow_missing, const std::string& why) {
    try {
      merge_shards({first.folder, second.folder}, (dir_ / "merged").string(), allow_missing);
      ADD_FAILURE() << "merged a shard being written (" << why << ")";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("shard 2 is still being written by a deepvox process"),
                std::string::npos)
          << e.what();
    }
  };
  {
    // A resume holds both locks.
    RunState state;
    RunJournal journal = RunJournal::reopen(second.folder, state);
    expect_refused(true, "flock and writer.lock");
  }
  {
    // writer.lock alone (as on a file system without flock).
    const WriterLock lock = WriterLock::take(second.folder);
    EXPECT_TRUE(read_run_state(second.folder).locked);
    expect_refused(true, "writer.lock");
  }
  // Released: the killed shard (journal marked running, nobody writing) merges only as a part.
  EXPECT_FALSE(read_run_state(second.folder).locked);
  EXPECT_NO_THROW(merge_shards({first.folder, second.folder}, (dir_ / "merged").string(), true));
}

// A lock file written as another process would have.
void write_lock(const fs::path& dir, const Json& lock) {
  std::ofstream(dir / "writer.lock") << lock.dump() << "\n";
}

TEST(WriterLock, KeepsOneWriterAndTakesOverStaleLocks) {
  const fs::path dir = scratch_dir("test_harness_tmp");
  {
    const WriterLock mine = WriterLock::take(dir);
    const LockHolder holder = writer_lock_holder(dir);
    EXPECT_TRUE(holder.held && holder.checked);
    EXPECT_NE(holder.who.find("pid " + std::to_string(getpid()) + " on host " + host_name()),
              std::string::npos)
        << holder.who;
    try {
      WriterLock::take(dir);
      ADD_FAILURE() << "a second writer took the lock";
    } catch (const InputError& e) {
      EXPECT_NE(
          std::string(e.what()).find("another deepvox process (pid " + std::to_string(getpid())),
          std::string::npos)
          << e.what();
    }
  }
  EXPECT_FALSE(fs::exists(dir / "writer.lock")) << "released, the lock file stays";
  EXPECT_FALSE(writer_lock_holder(dir).held);

  // This host, a process that ended: stale.
  const pid_t ended = fork();
  if (ended == 0) _exit(0);
  waitpid(ended, nullptr, 0);
  write_lock(dir, {{"host", host_name()}, {"pid", ended}, {"start_ticks", 12345}});
  EXPECT_FALSE(writer_lock_holder(dir).held);
  EXPECT_NO_THROW(WriterLock::take(dir).release());
  // This host, our pid with another start time (the pid reused): stale.
  write_lock(dir, {{"host", host_name()}, {"pid", getpid()}, {"start_ticks", 1}});
  EXPECT_FALSE(writer_lock_holder(dir).held);

  // Another host, touched lately: held, unchecked; refused naming it.
  write_lock(dir, {{"host", "node-elsewhere"}, {"pid", 42}, {"since", "then"}});
  LockHolder other = writer_lock_holder(dir);
  EXPECT_TRUE(other.held);
  EXPECT_FALSE(other.checked);
  try {
    WriterLock::take(dir);
    ADD_FAILURE() << "took a lock another host holds";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("pid 42 on host node-elsewhere"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("another host"), std::string::npos) << e.what();
  }
  // ... the same SLURM job started again (requeued after a node failure): stale.
  write_lock(dir,
             {{"host", "node-elsewhere"}, {"pid", 42}, {"slurm_job", "777"}, {"slurm_restart", 0}});
  setenv("SLURM_JOB_ID", "777", 1);
  setenv("SLURM_RESTART_COUNT", "1", 1);
  EXPECT_FALSE(writer_lock_holder(dir).held);
  setenv("SLURM_RESTART_COUNT", "0", 1);
  EXPECT_TRUE(writer_lock_holder(dir).held) << "the same run of the job is no restart";
  unsetenv("SLURM_JOB_ID");
  unsetenv("SLURM_RESTART_COUNT");
  // ... no heartbeat for 10 minutes (the node failed): stale, taken over.
  const timespec old[2] = {{std::time(nullptr) - 600, 0}, {std::time(nullptr) - 600, 0}};
  ASSERT_EQ(utimensat(AT_FDCWD, (dir / "writer.lock").c_str(), old, 0), 0);
  EXPECT_FALSE(writer_lock_holder(dir).held);
  const WriterLock taken = WriterLock::take(dir);
  EXPECT_TRUE(writer_lock_holder(dir).checked);
}

// flock replaced (LD_PRELOAD) by one that fails as on Lustre mounted noflock: the run says so,
// and while a live process holds the folder's writer.lock (this test, without any flock), a
// `deepvox suite --resume` of it is refused; once released, the resume completes the rows.
TEST_F(LongRuns, WithoutFlockTheLockFileKeepsOneWriter) {
  const std::string preload = std::string("LD_PRELOAD=") + DEEPVOX_FLOCK_FAILS_LIBRARY +
                              " ASAN_OPTIONS=${ASAN_OPTIONS:-}:verify_asan_link_order=0 ";
  const SuiteOutcome plain = run("plain");
  const fs::path out = dir_ / "out", root = out / "resumable";
  const auto deepvox = [&](const std::string& args) {
    const std::string command =
        preload + kBinary + " " + args + " > " + (dir_ / "run.log").string() + " 2>&1";
    const int status = std::system(command.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  };
  ASSERT_EQ(deepvox("suite " + suite_ + " --backend cpu --costs estimate --out " + out.string()), 0)
      << read(dir_ / "run.log");
  EXPECT_NE(read(dir_ / "run.log")
                .find("the file system has no flock (Function not implemented); one writer per "
                      "folder is kept by its writer.lock"),
            std::string::npos)
      << read(dir_ / "run.log");
  const std::vector<fs::path> folders = result_folders(root);
  ASSERT_EQ(folders.size(), 1u);
  simulate_kill(folders[0], 3);
  {
    const WriterLock writing = WriterLock::take(folders[0]);  // no flock taken
    EXPECT_EQ(deepvox("suite " + suite_ + " --resume " + folders[0].string()), 2)
        << read(dir_ / "run.log");
    EXPECT_NE(
        read(dir_ / "run.log").find("another deepvox process (pid " + std::to_string(getpid())),
        std::string::npos)
        << read(dir_ / "run.log");
  }
  ASSERT_EQ(deepvox("suite " + suite_ + " --resume " + folders[0].string()), 0)
      << read(dir_ / "run.log");
  EXPECT_EQ(untimed_rows_file(folders[0]), untimed_rows_file(plain.folder));
  expect_no_duplicates(folders[0]);
  EXPECT_FALSE(fs::exists(folders[0] / "writer.lock"));
}

// The maps of one sweep value cannot fit the card (a 3D-texture atlas of 4096^2 texels and 4096
// layers of 8 bytes: 550 GB): that row fails with out_of_memory and the bytes, its memory is
// given back, and the next rows run on the device.
TEST_F(LongRuns, CudaOutOfMemoryOnTheCardFailsOneRowAndTheNextRowsRun) {
  std::string why;
  if (!cuda_device_available(&why)) GTEST_SKIP() << "needs a GPU: " << why;
  const std::string scene = source_dir() + "/experiments/scenes/demo.json";
  const auto suite_of = [&](const std::string& file, const std::string& resolutions) {
    return write(file, R"({"suite": "oom", "repeat": 1, "experiments": [
    {"name": "e", "kind": "shadow", "scene": ")" +
                           scene +
                           R"(", "strategy": "dsm",
     "params": {"storage": "texture3d", "storage.sizing": "thesis", "storage.layers": 4096},
     "sweep": {"res": [)" + resolutions +
                           R"(]},
     "settings": {"width": 40, "height": 30, "probe_points": 20, "images": 0}}]})");
  };
  const std::string suite = suite_of("oom.json", "16, 4096, 32");
  // The rows that fit, run once first: what a process keeps after its first CUDA work (loaded
  // kernel modules, local memory sized for the kernels that ran, the pool's high water) is not
  // the failed row's to give back.
  SuiteOptions warm = cpu_options(suite_of("warm.json", "16, 32"));
  warm.backend = "cuda";
  warm.report = false;
  warm.out += "-warm";
  ASSERT_EQ(run_suite(warm).failed, 0);
  const int64_t card = int64_t(cuda_device_info().memory_bytes);
  const int64_t free_before = free_memory_bytes(Memory::device);
  SuiteOptions o = cpu_options(suite);
  o.backend = "cuda";
  o.report = false;
  const SuiteOutcome r = run_suite(o);
  EXPECT_EQ(r.exit_code, kSuiteRowsFailed);
  EXPECT_EQ(r.failed, 1);
  std::map<int, std::map<std::string, Row>> by_item;
  for (const Row& row : read_rows_csv(r.folder + "/rows.csv"))
    by_item[row.item][row.metric + ":" + row.stat] = row;
  ASSERT_TRUE(by_item[1].count("out_of_memory:bytes_asked"));
  const double asked = by_item[1]["out_of_memory:bytes_asked"].value;
  EXPECT_GT(asked, double(card)) << "the atlas fits the card: raise res";
  EXPECT_NE(by_item[1]["failed:value"].note.find("out of memory: dsm texture3d atlas"),
            std::string::npos)
      << by_item[1]["failed:value"].note;
  for (int item : {0, 2}) {
    EXPECT_FALSE(by_item[item].count("failed:value")) << "item " << item;
    EXPECT_TRUE(by_item[item].count("bytes:value")) << "item " << item << " did not run";
  }
  // Given back: what the device can hand out is what it was (the pool keeps freed memory, and
  // counts it as free), within 64 MB of other processes on a shared card.
  EXPECT_GT(free_memory_bytes(Memory::device), free_before - (int64_t(64) << 20));
  std::printf("out_of_memory row: %.0f bytes asked on a card of %lld bytes\n", asked,
              (long long)card);
}

}  // namespace
}  // namespace dv
