// Worker processes on one node (workers.h).
#include "experiments/harness/workers.h"

#include <fcntl.h>
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
#include "experiments/harness/interrupt.h"
#include "experiments/harness/merge.h"
#include "experiments/harness/progress.h"
#include "experiments/harness/report.h"
#include "experiments/harness/run_folder.h"
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
  fs::path status, log;
};

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
            const fs::path& log) {
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
  posix_spawn_file_actions_addopen(&files, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                   0644);
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
  const std::string suite_path = fs::absolute(resolve_suite_path(o.suite)).string();
  const Suite suite = load_suite(suite_path);
  const std::string costs = fixed_cost_source(o, suite);
  const fs::path session =
      make_run_folder(o.out, suite.name, build_git_sha(), std::to_string(count) + "workers");
  const bool cpu = o.backend == "cpu";
  const int threads = std::max(1, cpu_thread_count() / count);
  const std::string exe = fs::read_symlink("/proc/self/exe").string();
  std::vector<std::string> gpus = cpu ? std::vector<std::string>{} : visible_gpus();
  if (!cpu && int(gpus.size()) < count)
    throw InputError("--gpus", std::to_string(count) + " workers asked for, " +
                                   std::to_string(gpus.size()) + " GPU(s) visible");
  const InterruptScope ctrl_c;  // a Ctrl-C stops the workers after their current experiment
  std::vector<Worker> workers(static_cast<size_t>(count));
  for (int i = 0; i < count; ++i) {
    Worker& w = workers[size_t(i)];
    w.status = session / ("worker" + std::to_string(i + 1) + ".status");
    w.log = session / ("worker" + std::to_string(i + 1) + ".log");
    std::vector<std::string> args =
        shard_arguments(o, suite_path, i + 1, count, (session / "shards").string(), costs);
    args.insert(args.begin(), exe);
    args.insert(args.end(), {"--status-file", w.status.string()});
    const std::string env = cpu ? "DEEPVOX_THREADS=" + std::to_string(threads)
                                : "CUDA_VISIBLE_DEVICES=" + gpus[size_t(i)];
    w.pid = spawn(args, {env}, w.log);
  }
  const bool terminal = o.progress && Progress::stderr_is_terminal();
  for (bool first = true, running = true; running; first = false) {
    running = false;
    for (Worker& w : workers) {
      if (w.exit_code >= 0) continue;
      int status = 0;
      if (waitpid(w.pid, &status, WNOHANG) == w.pid)
        w.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      else
        running = true;
    }
    if (terminal) show(workers, !first);
    if (running) std::this_thread::sleep_for(std::chrono::milliseconds(250));
  }
  std::vector<std::string> folders;
  const fs::path shard_root = session / "shards" / suite.name;
  if (fs::is_directory(shard_root))
    for (const auto& entry : fs::directory_iterator(shard_root))
      folders.push_back(entry.path().string());
  std::sort(folders.begin(), folders.end());
  SuiteOutcome outcome;
  for (size_t i = 0; i < workers.size(); ++i)
    if (workers[i].exit_code != 0 && workers[i].exit_code != 3)
      std::fprintf(stderr, "deepvox suite: worker %zu exited %d (log: %s)\n", i + 1,
                   workers[i].exit_code, workers[i].log.c_str());
  outcome.folder = merge_shards(folders, o.out, true);
  const Json meta = parse_json_file((fs::path(outcome.folder) / "meta.json").string());
  outcome.done = meta["done"].get<int>();
  outcome.total = meta["items"].get<int>();
  outcome.failed = meta["failed"].get<int>();
  outcome.skipped = meta["skipped"].get<int>();
  outcome.interrupted = meta["interrupted"].get<bool>();
  for (const Worker& w : workers)
    outcome.exit_code =
        std::max(outcome.exit_code,
                 w.exit_code == 0 || w.exit_code == 3 || w.exit_code == 130 ? w.exit_code : 3);
  if (meta.contains("missing_shards")) outcome.exit_code = std::max(outcome.exit_code, 3);
  return outcome;
}

SuiteOutcome run_rounds(const SuiteOptions& o, int runs) {
  if (runs < 1) throw InputError("--runs", "expected a positive count");
  const std::string suite_path = fs::absolute(resolve_suite_path(o.suite)).string();
  const Suite suite = load_suite(suite_path);
  const fs::path session =
      make_run_folder(o.out, suite.name, build_git_sha(), std::to_string(runs) + "runs");
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
