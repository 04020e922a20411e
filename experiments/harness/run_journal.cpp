// Result folders as journals (run_journal.h).
#include "experiments/harness/run_journal.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <set>

#include "core/error.h"

namespace dv {

namespace fs = std::filesystem;

namespace {

constexpr const char* kProgress = "progress.jsonl";

// One marker line, or a null Json when the line is no whole marker.
Json parse_marker(const std::string& line) {
  const Json m = Json::parse(line, nullptr, false);
  if (m.is_discarded() || !m.is_object()) return Json();
  for (const char* key : {"item", "rows", "rows_end"})
    if (!m.contains(key) || !m[key].is_number_integer()) return Json();
  if (!m.contains("outcome") || !m["outcome"].is_string()) return Json();
  return m;
}

// Reads progress.jsonl against rows.csv: each whole marker line whose row group (the bytes
// since the previous marker's end) parses to exactly its rows of its item counts; the first
// line that does not ends the complete part.
void read_journal(RunState& s, const std::string& rows_text, const std::string& progress_text) {
  const std::string rows_path = (s.dir / "rows.csv").string();
  int64_t end = int64_t(rows_csv_body_start(rows_text, rows_path));
  s.rows_end = end;
  std::set<int> seen;
  std::map<int, std::vector<Row>> groups;
  std::map<int, Json> params;
  size_t at = 0;
  while (at < progress_text.size()) {
    const size_t newline = progress_text.find('\n', at);
    if (newline == std::string::npos) break;  // a torn last line
    const Json m = parse_marker(progress_text.substr(at, newline - at));
    if (m.is_null()) break;
    const int item = m["item"].get<int>();
    const int64_t group_end = m["rows_end"].get<int64_t>();
    if (seen.count(item) || group_end < end || group_end > int64_t(rows_text.size())) break;
    std::vector<Row> group;
    try {
      group = parse_rows_csv(rows_text.substr(size_t(end), size_t(group_end - end)), rows_path, 0);
    } catch (const InputError&) {
      break;
    }
    if (int(group.size()) != m["rows"].get<int>() ||
        std::any_of(group.begin(), group.end(), [&](const Row& r) { return r.item != item; }))
      break;
    seen.insert(item);
    groups[item] = std::move(group);
    params[item] = m.value("params", Json::object());
    s.attempt_of.emplace_back(item, m.value("attempt", 1));
    const std::string outcome = m["outcome"].get<std::string>();
    s.failed += outcome == "failed";
    s.skipped += outcome == "skipped";
    end = group_end;
    s.rows_end = end;
    s.progress_end = int64_t(newline + 1);
    at = newline + 1;
  }
  for (auto& [item, group] : groups) {
    s.rows.insert(s.rows.end(), group.begin(), group.end());
    s.params.push_back(params[item]);
  }
  s.done = int(seen.size());
  for (const Json& i : s.meta.value("planned_items", Json::array()))
    s.planned.push_back(i.get<int>());
  for (int i : s.planned)
    if (!seen.count(i)) s.missing.push_back(i);
  s.finished = s.missing.empty() && s.meta.value("state", "") == "finished";
}

// Says once per folder that its file system has no flock, so that the lock file alone keeps
// one writer per folder.
void note_missing_flock(const fs::path& where, const std::string& no_locks) {
  if (no_locks.empty()) return;
  std::fprintf(stderr,
               "deepvox suite: note: %s: the file system has no flock (%s); one writer per "
               "folder is kept by its writer.lock (host and pid) alone\n",
               where.c_str(), no_locks.c_str());
}

}  // namespace

Json read_run_meta(const fs::path& dir) {
  const fs::path path = dir / "meta.json";
  if (!fs::is_regular_file(path))
    throw InputError(dir.string(), "not a suite result folder (no meta.json)");
  return parse_json_file(path.string());
}

RunState read_run_state(const fs::path& dir) {
  RunState s;
  s.dir = dir;
  s.meta = read_run_meta(dir);
  s.journaled = fs::is_regular_file(dir / kProgress);
  if (s.journaled) {
    const LockHolder writer = writer_lock_holder(dir);
    s.locked = file_is_locked(dir / kProgress) || writer.checked;
    if (writer.held && !writer.checked) s.unchecked_writer = writer.who;
    read_journal(s, read_file_text(dir / "rows.csv"), read_file_text(dir / kProgress));
    return s;
  }
  s.rows = read_rows_csv((dir / "rows.csv").string());
  sort_rows_by_item(s.rows);
  if (fs::is_regular_file(dir / "params.json"))
    s.params = parse_json_file((dir / "params.json").string());
  s.done = s.meta.value("done", 0);
  s.failed = s.meta.value("failed", 0);
  s.skipped = s.meta.value("skipped", 0);
  for (const Json& i : s.meta.value("missing_items", Json::array()))
    s.missing.push_back(i.get<int>());
  s.finished = true;
  return s;
}

fs::path newest_run(const fs::path& out, const std::string& suite, int shard_index, int shard_count,
                    bool unfinished_only) {
  std::vector<fs::path> runs;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(out / suite, ec)) {
    const fs::path dir = entry.path();
    if (dir.filename().string().rfind('.', 0) == 0 || !fs::is_regular_file(dir / kProgress) ||
        !fs::is_regular_file(dir / "meta.json"))
      continue;
    const Json meta = Json::parse(read_file_text(dir / "meta.json"), nullptr, false);
    if (meta.is_discarded() || (unfinished_only && meta.value("state", "") == "finished")) continue;
    const Json shard = meta.value("shard", Json::object());
    if (shard.value("index", 1) == shard_index && shard.value("count", 1) == shard_count)
      runs.push_back(dir);
  }
  std::sort(runs.begin(), runs.end());  // names begin with the UTC time
  return runs.empty() ? fs::path() : runs.back();
}

RunJournal RunJournal::create(const fs::path& out, const std::string& suite,
                              const std::string& git_sha, const std::string& tag, const Json& meta,
                              const std::string& suite_text, const std::string& command) {
  RunJournal j;
  j.dir_ = make_filled_run_folder(out, suite, git_sha, tag, [&](const fs::path& tmp) {
    write_file_atomically(tmp / "command.txt", command + "\n");
    write_file_atomically(tmp / "suite.json", suite_text);
    write_file_atomically(tmp / "meta.json", meta.dump(1) + "\n");
    j.rows_ = AppendFile(tmp / "rows.csv", true);
    j.rows_.append(rows_csv_header());
    j.progress_ = AppendFile(tmp / kProgress, true);
    std::string no_locks;
    j.progress_.try_lock(&no_locks);
    note_missing_flock(out, no_locks);
    j.lock_ = WriterLock::take(tmp);
  });
  j.rows_.set_path(j.dir_ / "rows.csv");
  j.progress_.set_path(j.dir_ / kProgress);
  j.lock_.set_dir(j.dir_);
  j.rows_end_ = j.rows_.size();
  return j;
}

RunJournal RunJournal::reopen(const fs::path& dir, RunState& state) {
  read_run_meta(dir);
  if (!fs::is_regular_file(dir / kProgress))
    throw InputError(
        dir.string(),
        "written by a deepvox that cannot resume (no progress.jsonl); start a new run");
  RunJournal j;
  j.dir_ = dir;
  j.progress_ = AppendFile(dir / kProgress, false);
  std::string no_locks;
  if (!j.progress_.try_lock(&no_locks))
    throw InputError(dir.string(),
                     "another deepvox process is writing this folder now; wait for it to end");
  note_missing_flock(dir, no_locks);
  j.lock_ = WriterLock::take(dir);
  state = read_run_state(dir);
  state.locked = false;  // the lock is ours
  j.rows_ = AppendFile(dir / "rows.csv", false);
  if (j.rows_.size() != state.rows_end) j.rows_.truncate(state.rows_end);
  if (j.progress_.size() != state.progress_end) j.progress_.truncate(state.progress_end);
  j.rows_end_ = state.rows_end;
  return j;
}

std::string RunJournal::resumed_suite_file(const fs::path& dir) {
  if (dir.empty())
    throw InputError("--resume", "give the suite (name or file), or the folder to resume");
  const std::string file = read_run_state(dir).meta.value("suite_file", "");
  if (!fs::is_regular_file(file))
    throw InputError(dir.string(), "its suite file " + file + " is gone; give the suite file");
  return file;
}

namespace {

std::string option_text(const Json& value) {
  return value.is_string() ? value.get<std::string>() : value.dump();
}

// InputError when `r` may not resume the folder `dir` whose meta.json is `meta`; `forced` gets
// what differs but --force allows.
void check_resumable(const JournalRequest& r, const fs::path& dir, const Json& meta,
                     std::vector<std::string>& forced) {
  if (meta.value("suite", "") != r.suite)
    throw InputError(dir.string(), "a run of suite '" + meta.value("suite", "") + "', not of '" +
                                       r.suite + "' (" + r.suite_file + ")");
  std::string problems;
  if (meta.value("suite_hash", "") != r.suite_hash) {
    forced.push_back("suite file");
    problems += "the suite file differs (the folder ran " + meta.value("suite_file", "") +
                " with hash " + meta.value("suite_hash", "") + ", " + r.suite_file + " has hash " +
                r.suite_hash + ")";
  }
  const std::string folder_sha = meta["run"].value("git_sha", "");
  if (folder_sha != r.git_sha) {
    forced.push_back("commit");
    problems += std::string(problems.empty() ? "" : "; ") + "the commit differs (the folder ran " +
                folder_sha + ", this deepvox is " + r.git_sha + ")";
  }
  if (!forced.empty() && !r.force)
    throw InputError(dir.string(), "cannot resume: " + problems +
                                       "; resume with the suite file and binary it ran, or add "
                                       "--force to mix them in one folder (its report says so)");
  for (const JournalRequest::GivenOption& option : r.given) {
    const Json folder = option.folder_value(meta);
    if (option.value != folder)
      throw InputError(option.name + " " + option_text(option.value),
                       dir.string() + " ran with " + option.name + " " + option_text(folder) +
                           "; leave the option out to resume it");
  }
}

}  // namespace

OpenedRun RunJournal::open_or_resume(const JournalRequest& r) {
  OpenedRun opened;
  if (!r.resume) {
    opened.journal = create(r.out, r.suite, r.git_sha, r.tag, r.meta, r.suite_text, r.command);
    return opened;
  }
  fs::path dir = r.resume_dir;
  if (dir.empty()) {
    dir = newest_unfinished_run(r.out, r.suite, r.shard_index, r.shard_count);
    if (dir.empty())
      throw InputError((r.out / r.suite).string(),
                       "no unfinished run of suite '" + r.suite + "'" +
                           (r.shard_count == 1 ? std::string()
                                               : " shard " + std::to_string(r.shard_index) + "/" +
                                                     std::to_string(r.shard_count)) +
                           " to resume (start one without --resume)");
  }
  check_resumable(r, dir, read_run_state(dir).meta, opened.forced);
  opened.journal = reopen(dir, opened.before);
  return opened;
}

void RunJournal::record(int item, int attempt, const std::vector<Row>& rows,
                        const std::string& outcome, const Json& params, double seconds) {
  const std::string text = rows_csv_text(rows);
  rows_.append(text);
  rows_end_ += int64_t(text.size());
  const Json marker = {{"item", item},          {"attempt", attempt}, {"rows", rows.size()},
                       {"rows_end", rows_end_}, {"outcome", outcome}, {"seconds", seconds},
                       {"params", params}};
  progress_.append(marker.dump() + "\n");
}

void RunJournal::write_meta(const Json& meta) const {
  write_file_atomically(dir_ / "meta.json", meta.dump(1) + "\n");
}

void RunJournal::add_command(const std::string& command) const {
  write_file_atomically(dir_ / "command.txt",
                        read_file_text(dir_ / "command.txt") + command + "\n");
}

void RunJournal::close() {
  rows_ = AppendFile();
  progress_ = AppendFile();
  lock_.release();
}

}  // namespace dv
