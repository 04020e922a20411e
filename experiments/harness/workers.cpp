// Worker processes on one node (workers.h).
#include "experiments/harness/workers.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "core/error.h"
#include "core/json_reader.h"
#include "core/parallel.h"
#include "experiments/harness/durable_file.h"
#include "experiments/harness/interrupt.h"
#include "experiments/harness/merge.h"
#include "experiments/harness/progress.h"
#include "experiments/harness/recorded_runs.h"
#include "experiments/harness/report.h"
#include "experiments/harness/run_folder.h"
#include "experiments/harness/run_journal.h"
#include "experiments/harness/run_metadata.h"
#include "experiments/harness/shard_plan.h"

extern char** environ;

namespace dv {

namespace fs = std::filesystem;

namespace {

// The GPUs a worker may be given: the entries of CUDA_VISIBLE_DEVICES when it is set, else
// 0 .. n-1 for the n lines "GPU k: ..." of `nvidia-smi -L`.
std::vector<std::string> visible_gpus() {
  std::vector<std::string> ids;
  if (const char* visible = std::getenv("CUDA_VISIBLE_DEVICES")) {
    std::stringstream list(visible);
    for (std::string id; std::getline(list, id, ',');)
      if (!id.empty()) ids.push_back(id);
    return ids;
  }
  FILE* pipe = popen("nvidia-smi -L 2>/dev/null", "r");
  if (!pipe) return ids;
  char line[512];
  while (fgets(line, sizeof line, pipe))
    if (std::string(line).rfind("GPU ", 0) == 0) ids.push_back(std::to_string(ids.size()));
  pclose(pipe);
  return ids;
}

struct Worker {
  pid_t pid = 0;
  int exit_code = -1;
  int restarts = 0;
  fs::path status, log;
};

// A worker killed by a signal is started again this often before its session stops unmerged.
constexpr int kMaxRestarts = 3;
constexpr const char* kSessionFile = "session.json";

// A `--gpus` session: OUT/<suite>/<date>_<sha>-Nworkers/ with session.json (suite, its file,
// the workers, the cost source fixed for every shard, the options, the state: "running" until
// merged, then "merged" and the merged folder) and the shards under shards/.
struct Session {
  fs::path dir;
  Json json;
  std::string suite, suite_path, costs;
  SuiteOptions options;  // what every worker runs with
};

Session new_session(const SuiteOptions& o, int count) {
  Session s;
  s.suite_path = fs::absolute(resolve_suite_path(o.suite)).string();
  const Suite suite = load_suite(s.suite_path);
  s.suite = suite.name;
  s.costs = fixed_cost_source(o, suite);
  s.options = o;
  s.dir = make_run_folder(o.out, suite.name, build_git_sha(), std::to_string(count) + "workers");
  s.json = {{"suite", s.suite}, {"suite_file", s.suite_path}, {"workers", count},
            {"costs", s.costs}, {"backend", o.backend},       {"repeat", o.repeat},
            {"only", o.only},   {"smoke", o.smoke},           {"state", "running"}};
  write_file_atomically(s.dir / kSessionFile, s.json.dump(1) + "\n");
  return s;
}

// The newest session of `suite` with `count` workers under OUT/<suite>/ that was not merged
// whole; empty when there is none.
fs::path newest_unmerged_session(const fs::path& out, const std::string& suite, int count) {
  std::vector<fs::path> found;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(out / suite, ec)) {
    if (!fs::is_regular_file(entry.path() / kSessionFile)) continue;
    const Json json = Json::parse(read_file_text(entry.path() / kSessionFile), nullptr, false);
    if (!json.is_discarded() && json.value("state", "") != "merged" &&
        json.value("workers", 0) == count)
      found.push_back(entry.path());
  }
  std::sort(found.begin(), found.end());  // names begin with the UTC time
  return found.empty() ? fs::path() : found.back();
}

// `--gpus N --resume [DIR]`: the session in DIR, or the newest unmerged one of the suite.
Session reopen_session(const SuiteOptions& o, int count) {
  Session s;
  std::string given_suite;
  if (!o.suite.empty()) given_suite = fs::absolute(resolve_suite_path(o.suite)).string();
  s.dir = o.resume_dir;
  if (s.dir.empty()) {
    if (given_suite.empty())
      throw InputError("--resume", "give the suite (name or file), or the session to resume");
    const std::string name = load_suite(given_suite).name;
    s.dir = newest_unmerged_session(o.out, name, count);
    if (s.dir.empty())
      throw InputError((fs::path(o.out) / name).string(),
                       "no unmerged --gpus " + std::to_string(count) + " session of suite '" +
                           name + "' to resume (start one without --resume)");
  }
  if (!fs::is_regular_file(s.dir / kSessionFile))
    throw InputError(s.dir.string(),
                     "not a --gpus session (no session.json); resume its "
                     "shards one by one (--shard I/N --resume DIR)");
  s.json = parse_json_file((s.dir / kSessionFile).string());
  s.suite = s.json.value("suite", "");
  s.suite_path = given_suite.empty() ? s.json.value("suite_file", "") : given_suite;
  const Suite suite = load_suite(s.suite_path);
  if (suite.name != s.suite)
    throw InputError(s.dir.string(), "a session of suite '" + s.suite + "', not of '" + suite.name +
                                         "' (" + s.suite_path + ")");
  if (s.json.value("workers", 0) != count)
    throw InputError("--gpus " + std::to_string(count),
                     s.dir.string() + " ran " + std::to_string(s.json.value("workers", 0)) +
                         " workers; resume it with as many");
  s.costs = s.json.value("costs", "estimate");
  s.options = o;
  s.options.backend = s.json.value("backend", "");
  s.options.repeat = s.json.value("repeat", 0);
  s.options.only = s.json.value("only", "");
  s.options.smoke = s.json.value("smoke", false);
  const auto differs = [&](bool given, bool same, const std::string& option) {
    if (given && !same)
      throw InputError(option, s.dir.string() + " ran with another " + option +
                                   "; leave the option out to resume it");
  };
  differs(!o.backend.empty(), o.backend == s.options.backend, "--backend");
  differs(o.repeat > 0, o.repeat == s.options.repeat, "--repeat");
  differs(!o.only.empty(), o.only == s.options.only, "--only");
  differs(o.smoke, o.smoke == s.options.smoke, "--smoke");
  return s;
}

// The outcome of `deepvox suite --gpus` read from its merged folder.
SuiteOutcome merged_outcome(const std::string& folder, int exit_code) {
  const Json meta = parse_json_file((fs::path(folder) / "meta.json").string());
  SuiteOutcome outcome;
  outcome.folder = folder;
  outcome.done = meta["done"].get<int>();
  outcome.total = meta["items"].get<int>();
  outcome.failed = meta["failed"].get<int>();
  outcome.skipped = meta["skipped"].get<int>();
  outcome.interrupted = meta["interrupted"].get<bool>();
  outcome.exit_code = std::max(exit_code, outcome.failed ? kSuiteRowsFailed : kSuiteDone);
  if (meta.contains("missing_shards")) outcome.exit_code = std::max(outcome.exit_code, 3);
  return outcome;
}

// One line per worker, rewritten in place on a terminal.
void show(const std::vector<Worker>& workers, bool redraw) {
  if (redraw) std::fprintf(stderr, "\033[%zuA", workers.size());
  for (size_t i = 0; i < workers.size(); ++i) {
    std::ifstream in(workers[i].status);
    int done = 0, total = 0;
    std::string what;
    in >> done >> total;
    std::getline(in >> std::ws, what);
    std::string line = std::to_string(done) + " of " + std::to_string(total) + " done: " + what;
    if (workers[i].exit_code >= 0) line += " (exit " + std::to_string(workers[i].exit_code) + ")";
    const std::string shown = line.size() > 90 ? line.substr(0, 87) + "..." : line;
    std::fprintf(stderr, "\r\033[Kworker %zu: %s\n", i + 1, shown.c_str());
  }
  std::fflush(stderr);
}

pid_t spawn(const std::vector<std::string>& args, const std::vector<std::string>& env_extra,
            const fs::path& log, bool append_log = false) {
  std::vector<std::string> env;
  for (char** e = environ; *e; ++e) {
    const std::string var = *e;
    bool replaced = false;
    for (const std::string& x : env_extra)
      replaced |= var.rfind(x.substr(0, x.find('=') + 1), 0) == 0;
    if (!replaced) env.push_back(var);
  }
  env.insert(env.end(), env_extra.begin(), env_extra.end());
  std::vector<char*> argv, envp;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  for (const std::string& e : env) envp.push_back(const_cast<char*>(e.c_str()));
  argv.push_back(nullptr);
  envp.push_back(nullptr);
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_addopen(&files, STDOUT_FILENO, log.c_str(),
                                   O_WRONLY | O_CREAT | (append_log ? O_APPEND : O_TRUNC), 0644);
  posix_spawn_file_actions_adddup2(&files, STDOUT_FILENO, STDERR_FILENO);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, argv[0], &files, nullptr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&files);
  if (rc != 0) throw Error("cannot start worker " + args[0] + ": " + std::strerror(rc));
  return pid;
}

}  // namespace

int worker_count(const std::string& gpus, const std::string& backend) {
  const bool cpu = backend == "cpu";
  if (gpus == "all") {
    const int n = cpu ? cpu_thread_count() : int(visible_gpus().size());
    if (n < 1)
      throw InputError("--gpus all",
                       "no GPU visible (for CPU worker processes: --backend cpu --gpus N)");
    return n;
  }
  char tail = 0;
  int n = 0;
  if (std::sscanf(gpus.c_str(), "%d%c", &n, &tail) != 1 || n < 1)
    throw InputError("--gpus", "expected a positive count or 'all', got '" + gpus + "'");
  return n;
}

std::string fixed_cost_source(const SuiteOptions& o, const Suite& suite) {
  if (!o.costs.empty()) return o.costs;
  return item_costs(filter_items(expand_suite(suite), o.only), suite, "", o.out).source;
}

std::vector<std::string> shard_arguments(const SuiteOptions& o, const std::string& suite_path,
                                         int index, int count, const std::string& shards_out,
                                         const std::string& costs) {
  std::vector<std::string> a = {
      "suite",      suite_path, "--shard", std::to_string(index) + "/" + std::to_string(count),
      "--out",      shards_out, "--costs", costs,
      "--no-report"};
  if (!o.backend.empty()) a.insert(a.end(), {"--backend", o.backend});
  if (o.repeat > 0) a.insert(a.end(), {"--repeat", std::to_string(o.repeat)});
  if (!o.only.empty()) a.insert(a.end(), {"--only", o.only});
  if (o.smoke) a.push_back("--smoke");
  return a;
}

SuiteOutcome run_workers(const SuiteOptions& o, int count) {
  const Session session = o.resume ? reopen_session(o, count) : new_session(o, count);
  const fs::path& dir = session.dir;
  const SuiteOptions& so = session.options;
  if (session.json.value("state", "") == "merged")
    return merged_outcome(session.json["merged"].get<std::string>(), kSuiteDone);
  const fs::path shards = dir / "shards";
  // Checked before any worker starts: a shard still being written stays with its writer.
  for (int k = 1; k <= count; ++k) {
    const fs::path folder = newest_run(shards, session.suite, k, count, false);
    if (!folder.empty() && read_run_state(folder).locked)
      throw InputError(folder.string(), "shard " + std::to_string(k) + " of " +
                                            std::to_string(count) +
                                            " is still being written by a deepvox process; "
                                            "resume when it ended");
  }
  const bool cpu = so.backend == "cpu";
  const int threads = std::max(1, cpu_thread_count() / count);
  const std::string exe = fs::read_symlink("/proc/self/exe").string();
  std::vector<std::string> gpus = cpu ? std::vector<std::string>{} : visible_gpus();
  if (!cpu && int(gpus.size()) < count)
    throw InputError("--gpus", std::to_string(count) + " workers asked for, " +
                                   std::to_string(gpus.size()) + " GPU(s) visible");
  const InterruptScope ctrl_c;  // a Ctrl-C stops the workers after their current experiment
  std::vector<Worker> workers(static_cast<size_t>(count));
  // Worker k runs shard k; when its shard has a folder (a resumed session, a restarted worker)
  // it resumes that folder.
  const auto start = [&](int k, bool append_log) {
    Worker& w = workers[size_t(k - 1)];
    std::vector<std::string> args =
        shard_arguments(so, session.suite_path, k, count, shards.string(), session.costs);
    args.insert(args.begin(), exe);
    args.insert(args.end(), {"--status-file", w.status.string()});
    const fs::path folder = newest_run(shards, session.suite, k, count, false);
    if (!folder.empty()) args.insert(args.end(), {"--resume", folder.string()});
    if (o.force) args.push_back("--force");
    const std::string env = cpu ? "DEEPVOX_THREADS=" + std::to_string(threads)
                                : "CUDA_VISIBLE_DEVICES=" + gpus[size_t(k - 1)];
    w.pid = spawn(args, {env}, w.log, append_log);
    w.exit_code = -1;
  };
  for (int k = 1; k <= count; ++k) {
    Worker& w = workers[size_t(k - 1)];
    w.status = dir / ("worker" + std::to_string(k) + ".status");
    w.log = dir / ("worker" + std::to_string(k) + ".log");
    start(k, o.resume);
  }
  const bool terminal = o.progress && Progress::stderr_is_terminal();
  for (bool first = true, running = true; running; first = false) {
    running = false;
    for (size_t i = 0; i < workers.size(); ++i) {
      Worker& w = workers[i];
      if (w.exit_code >= 0) continue;
      int status = 0;
      if (waitpid(w.pid, &status, WNOHANG) != w.pid) {
        running = true;
        continue;
      }
      w.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      // Killed (the out-of-memory killer, a stray kill): start it again on its shard's folder,
      // which resumes where it stopped, as a SLURM task requeues itself.
      if (WIFSIGNALED(status) && WTERMSIG(status) != SIGINT && w.restarts < kMaxRestarts &&
          !interrupt_requested()) {
        ++w.restarts;
        std::fprintf(stderr,
                     "deepvox suite: worker %zu ended by signal %d; restarting it to resume its "
                     "shard (restart %d of %d)\n",
                     i + 1, WTERMSIG(status), w.restarts, kMaxRestarts);
        start(int(i + 1), true);
        running = true;
      }
    }
    if (terminal) show(workers, !first);
    if (running) std::this_thread::sleep_for(std::chrono::milliseconds(250));
  }
  // A shard that did not finish for another reason than Ctrl-C is not merged as a part: the
  // session keeps its complete experiments and resumes.
  std::string unfinished;
  int failure = 0;
  bool interrupted = false;
  for (size_t i = 0; i < workers.size(); ++i) {
    const Worker& w = workers[i];
    interrupted |= w.exit_code == kSuiteInterrupted;
    if (w.exit_code == kSuiteDone || w.exit_code == kSuiteRowsFailed ||
        w.exit_code == kSuiteInterrupted)
      continue;
    unfinished += "\n  shard " + std::to_string(i + 1) + " of " + std::to_string(count) +
                  ": its worker exited " + std::to_string(w.exit_code) +
                  (w.restarts ? " after " + std::to_string(w.restarts) + " restart(s)" : "") +
                  " (log: " + w.log.string() + ")";
    // The exit code says the gravest: a full disk (free space first), bad input, an error.
    const int rank = w.exit_code == kSuiteStopped ? 3 : w.exit_code == 2 ? 2 : 1;
    failure = std::max(failure, rank);
  }
  if (failure) {
    const std::string message =
        "the session " + dir.string() + " is not merged, a shard did not finish:" + unfinished +
        "\nits complete experiments are kept; resume: deepvox suite " + session.suite_path +
        " --gpus " + std::to_string(count) + " --resume " + dir.string();
    if (failure == 3) throw ResultWriteError(message);
    if (failure == 2) throw InputError("", message);
    throw Error(message);
  }
  std::vector<std::string> folders;
  for (int k = 1; k <= count; ++k) {
    const fs::path folder = newest_run(shards, session.suite, k, count, false);
    if (!folder.empty()) folders.push_back(folder.string());
  }
  const std::string merged = merge_shards(folders, so.out, interrupted);
  Json json = session.json;
  json["merged"] = merged;
  if (!interrupted) json["state"] = "merged";
  write_file_atomically(dir / kSessionFile, json.dump(1) + "\n");
  int code = kSuiteDone;
  for (const Worker& w : workers) code = std::max(code, w.exit_code);
  return merged_outcome(merged, code);
}

SuiteOutcome run_rounds(const SuiteOptions& o, int runs) {
  if (runs < 1) throw InputError("--runs", "expected a positive count");
  const std::string suite_path = fs::absolute(resolve_suite_path(o.suite)).string();
  const Suite suite = load_suite(suite_path);
  const fs::path session =
      make_run_folder(o.out, suite.name, build_git_sha(),
                      std::to_string(runs) + "runs" + (o.permute ? "-replicate" : ""));
  const std::string exe = fs::read_symlink("/proc/self/exe").string();
  const InterruptScope ctrl_c;  // a Ctrl-C stops the round after its current experiment
  std::vector<std::string> folders;
  SuiteOutcome outcome;
  for (int k = 1; k <= runs && !interrupt_requested(); ++k) {
    std::vector<std::string> args = {exe,     "suite",          suite_path,
                                     "--out", session.string(), "--no-report"};
    if (!o.backend.empty()) args.insert(args.end(), {"--backend", o.backend});
    if (o.repeat > 0) args.insert(args.end(), {"--repeat", std::to_string(o.repeat)});
    if (!o.only.empty()) args.insert(args.end(), {"--only", o.only});
    if (o.smoke) args.push_back("--smoke");
    if (o.permute) args.insert(args.end(), {"--order-seed", std::to_string(o.order_seed + k - 1)});
    const fs::path log = session / ("run" + std::to_string(k) + ".log");
    std::fprintf(stderr, "deepvox suite: run %d of %d (log: %s)\n", k, runs, log.c_str());
    const pid_t pid = spawn(args, {}, log);
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    // The round's folder: the one under the session that is not yet known.
    const fs::path root = session / suite.name;
    std::vector<std::string> now;
    if (fs::is_directory(root))
      for (const auto& entry : fs::directory_iterator(root))
        if (std::find(folders.begin(), folders.end(), entry.path().string()) == folders.end())
          now.push_back(entry.path().string());
    if (now.size() != 1)
      throw Error("run " + std::to_string(k) + " of " + std::to_string(runs) + " exited " +
                  std::to_string(code) + " without one result folder (log: " + log.string() + ")");
    folders.push_back(now.front());
    outcome.exit_code = std::max(outcome.exit_code, code == 0 || code == 3 ? code : 3);
    if (code == 130) {
      outcome.exit_code = 130;
      outcome.interrupted = true;
      break;
    }
  }
  if (folders.empty()) throw Error("no run of " + std::to_string(runs) + " started");
  outcome.folder = folders.front();
  record_runs(outcome.folder, std::vector<std::string>(folders.begin() + 1, folders.end()));
  if (o.report) build_report(outcome.folder);
  const Json meta = parse_json_file((fs::path(outcome.folder) / "meta.json").string());
  outcome.done = meta.value("done", 0);
  outcome.total = meta.value("items", 0);
  outcome.failed = meta.value("failed", 0);
  outcome.skipped = meta.value("skipped", 0);
  return outcome;
}

}  // namespace dv
