// A suite run's result folder as a journal that survives being killed at any instant (SIGKILL,
// SLURM preemption, a full disk): meta.json (with the planned items), suite.json and
// command.txt exist before any experiment runs; each experiment appends its row group to
// rows.csv, syncs it, then appends one completion marker line to progress.jsonl (item, row
// count, end offset in rows.csv, outcome, echoed parameters) and syncs that. A row group
// without its marker is ignored by every reader and cut off on resume, so a group is whole or
// absent. docs/suite-format.md, "Killed runs and --resume", describes the files.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "core/json_reader.h"
#include "experiments/harness/durable_file.h"
#include "experiments/harness/rows.h"
#include "experiments/harness/writer_lock.h"

namespace dv {

// What a result folder holds now, complete parts only.
struct RunState {
  std::filesystem::path dir;
  Json meta;
  bool journaled = false;        // has progress.jsonl (written by a deepvox that resumes)
  bool finished = false;         // every planned item complete and the run ended (meta "state")
  bool locked = false;           // a process is writing the folder now (flock, writer.lock)
  std::string unchecked_writer;  // writer.lock names a process on another host that may run
  std::vector<Row> rows;         // complete row groups, in item order
  Json params = Json::array();   // echoed parameters per complete item, in item order
  std::vector<int> planned;      // items the run is to run (journaled folders)
  std::vector<int> missing;      // planned items without a complete row group
  std::vector<std::pair<int, int>> attempt_of;  // (item, attempt that ran it)
  int done = 0, failed = 0, skipped = 0;
  int64_t rows_end = 0;      // bytes of rows.csv that hold complete groups
  int64_t progress_end = 0;  // bytes of progress.jsonl that hold whole marker lines
};

// InputError naming the folder when it has no meta.json or a malformed file. Folders of
// earlier versions (no progress.jsonl) and merged folders read as finished, their counts from
// meta.json.
RunState read_run_state(const std::filesystem::path& dir);

// A result folder's meta.json alone (no rows read); InputError naming the folder when it has none
// or it is malformed.
Json read_run_meta(const std::filesystem::path& dir);

// The newest journaled folder under OUT/<suite>/ of shard I/N (1/1: an unsharded run), whose
// run did not finish when `unfinished_only`; empty when there is none.
std::filesystem::path newest_run(const std::filesystem::path& out, const std::string& suite,
                                 int shard_index, int shard_count, bool unfinished_only);
inline std::filesystem::path newest_unfinished_run(const std::filesystem::path& out,
                                                   const std::string& suite, int shard_index,
                                                   int shard_count) {
  return newest_run(out, suite, shard_index, shard_count, true);
}

// What a suite run asks of its result folder (RunJournal::open_or_resume): a new folder, or the
// folder of a killed or stopped run to continue, checked first to be a run of the same suite,
// suite file, commit and options.
struct JournalRequest {
  std::filesystem::path out;  // OUT: folders are OUT/<suite>/<date>_<sha>[-TAG]
  std::string suite;          // the suite's name
  std::string suite_file;     // the suite file this process runs
  std::string suite_hash;     // its hash
  std::string git_sha;        // this deepvox's commit
  int shard_index = 1, shard_count = 1;
  // A new run: the folder name's tag, its meta.json, the suite file's text and the command line.
  std::string tag;
  Json meta;
  std::string suite_text, command;
  // --resume: continue resume_dir, or without it the newest unfinished run of this suite and
  // shard under `out`; force: even when the suite file or the commit differ.
  bool resume = false;
  std::filesystem::path resume_dir;
  bool force = false;
  // Options given again on --resume: each must say what the folder ran with, which
  // `folder_value` reads from the folder's meta.json.
  struct GivenOption {
    std::string name;  // "--backend"
    Json value;        // as given now
    std::function<Json(const Json& meta)> folder_value;
  };
  std::vector<GivenOption> given;
};

struct OpenedRun;

// The writing side, held for the whole run (it keeps the folder locked: a flock on
// progress.jsonl and the lock file writer.lock, writer_lock.h).
class RunJournal {
 public:
  // A new folder OUT/<suite>/<date>_<sha>[-TAG] holding command.txt, suite.json, meta.json,
  // rows.csv (the header) and an empty progress.jsonl, made under a hidden name and renamed
  // into place (durable_file.h).
  static RunJournal create(const std::filesystem::path& out, const std::string& suite,
                           const std::string& git_sha, const std::string& tag, const Json& meta,
                           const std::string& suite_text, const std::string& command);
  // An existing folder to resume: locks it (InputError when another process writes it: flock,
  // or writer.lock where the file system has no flock), reads its state and cuts rows.csv and
  // progress.jsonl back to the complete part.
  static RunJournal reopen(const std::filesystem::path& dir, RunState& state);
  // The one door to a suite run's folder: without `resume` a new folder (create); with it the
  // folder to continue (the given one, else the newest unfinished run of the suite and shard),
  // checked before it is touched (a refused resume leaves it as it was): a run of the same
  // suite, and of the same suite file and commit unless `force`, every given option equal to
  // the folder's; then reopened. InputError naming the folder and what differs otherwise.
  static OpenedRun open_or_resume(const JournalRequest& request);
  // The suite file the run in `dir` ran, for a --resume DIR that names no suite; InputError when
  // `dir` is empty or the file is gone.
  static std::string resumed_suite_file(const std::filesystem::path& dir);

  const std::filesystem::path& dir() const { return dir_; }
  // Appends one item's rows, then its completion marker (with the item's wall-clock `seconds`),
  // each synced; ResultWriteError when the disk is full or the folder unwritable (the folder
  // stays resumable).
  void record(int item, int attempt, const std::vector<Row>& rows, const std::string& outcome,
              const Json& params, double seconds);
  // meta.json, written atomically.
  void write_meta(const Json& meta) const;
  // Appends a line to command.txt (atomically rewritten).
  void add_command(const std::string& command) const;
  // Closes the files and removes writer.lock, which releases the folder's lock.
  void close();

 private:
  std::filesystem::path dir_;
  AppendFile rows_, progress_;
  WriterLock lock_;
  int64_t rows_end_ = 0;
};

struct OpenedRun {
  RunJournal journal;
  RunState before;                  // the folder's complete part (empty for a new run)
  std::vector<std::string> forced;  // what a --force resume let differ: "suite file", "commit"
};

}  // namespace dv
