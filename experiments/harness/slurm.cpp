// SLURM job scripts for a sharded suite run (slurm.h).
#include "experiments/harness/slurm.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <vector>

#include "core/error.h"
#include "experiments/harness/durable_file.h"
#include "experiments/harness/run_folder.h"
#include "experiments/harness/run_journal.h"
#include "experiments/harness/run_metadata.h"
#include "experiments/harness/suite_file.h"
#include "experiments/harness/workers.h"

namespace dv {

namespace fs = std::filesystem;

namespace {

// Single-quoted for bash.
std::string quoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string header(const std::string& name, const SlurmOptions& s, const std::string& log) {
  std::string h = "#!/bin/bash\n#SBATCH --job-name=" + name + "\n#SBATCH --ntasks=1\n";
  if (!s.partition.empty()) h += "#SBATCH --partition=" + s.partition + "\n";
  if (!s.time.empty()) h += "#SBATCH --time=" + s.time + "\n";
  return h + "#SBATCH --output=" + log + "\n";
}

// Runs `command`, returns its first output line; Error naming it when it fails.
std::string run_command(const std::string& command) {
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) throw Error("cannot run " + command);
  std::string output;
  char buf[512];
  while (fgets(buf, sizeof buf, pipe)) output += buf;
  if (pclose(pipe) != 0) throw Error(command + " failed: " + output);
  return output.substr(0, output.find('\n'));
}

// Prints the two sbatch lines, or with `submit` runs them (the merge after the array ended).
int submit_or_print(const fs::path& array, const fs::path& merge, const SuiteOptions& o,
                    const SlurmOptions& s, int tasks, const std::string& suite) {
  if (!s.submit) {
    std::printf(
        "deepvox suite: wrote %s and %s\nsubmit: jid=$(sbatch --parsable %s) && sbatch "
        "--dependency=afterany:$jid %s\n",
        array.c_str(), merge.c_str(), array.c_str(), merge.c_str());
    return 0;
  }
  std::string job = run_command("sbatch --parsable " + quoted(array.string()));
  job = job.substr(0, job.find(';'));  // "id;cluster" on federations
  const std::string merge_job =
      run_command("sbatch --parsable --dependency=afterany:" + job + " " + quoted(merge.string()));
  std::printf(
      "deepvox suite: submitted array job %s (%d tasks) and merge job %s; merged report "
      "under %s/%s/ when done\n",
      job.c_str(), tasks, merge_job.substr(0, merge_job.find(';')).c_str(),
      fs::absolute(o.out).c_str(), suite.c_str());
  return 0;
}

// `--slurm --resume [DIR]`: the session's own scripts once more (DIR, else the newest SLURM
// session of the suite under --out). Their tasks resume their shards' folders, so a session
// whose array job was cancelled, ran out of time or of requeues continues where it stopped.
// Options that differ from the scripts' are refused; so is a shard still being written here.
int resume_slurm_session(const SuiteOptions& o, const SlurmOptions& s) {
  fs::path dir = o.resume_dir;
  if (dir.empty()) {
    if (o.suite.empty())
      throw InputError("--resume", "give the suite (name or file), or the session to resume");
    const std::string name = load_suite(resolve_suite_path(o.suite)).name;
    std::vector<fs::path> sessions;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(fs::path(o.out) / name, ec))
      if (fs::is_regular_file(entry.path() / "slurm" / "array.sbatch"))
        sessions.push_back(entry.path());
    std::sort(sessions.begin(), sessions.end());  // names begin with the UTC time
    if (sessions.empty())
      throw InputError((fs::path(o.out) / name).string(),
                       "no --slurm session of suite '" + name + "' to resume");
    dir = sessions.back();
  }
  const fs::path array = dir / "slurm" / "array.sbatch", merge = dir / "slurm" / "merge.sbatch";
  if (!fs::is_regular_file(array) || !fs::is_regular_file(merge))
    throw InputError(dir.string(),
                     "not a --slurm session (no slurm/array.sbatch and merge.sbatch)");
  const std::string script = read_file_text(array);
  const size_t at = script.find("#SBATCH --array=1-");
  const int tasks = at == std::string::npos ? 0 : std::atoi(script.c_str() + at + 18);
  if (tasks < 1) throw InputError(array.string(), "no '#SBATCH --array=1-N' line");
  if (s.tasks > 0 && s.tasks != tasks)
    throw InputError("--gpus " + std::to_string(s.tasks),
                     dir.string() + " has " + std::to_string(tasks) +
                         " tasks; resume it with as many (or leave --gpus out)");
  const auto require = [&](bool given, const std::string& text, const std::string& option) {
    if (given && script.find(text) == std::string::npos)
      throw InputError(option, array.string() + " runs with another " + option +
                                   "; leave the option out to resume it (or edit the script)");
  };
  require(!s.partition.empty(), "#SBATCH --partition=" + s.partition + "\n", "--partition");
  require(!s.time.empty(), "#SBATCH --time=" + s.time + "\n", "--time");
  require(!o.backend.empty(), "'--backend' " + quoted(o.backend), "--backend");
  require(o.repeat > 0, "'--repeat' " + quoted(std::to_string(o.repeat)), "--repeat");
  require(!o.only.empty(), "'--only' " + quoted(o.only), "--only");
  require(o.smoke, "'--smoke'", "--smoke");
  std::string suite;
  std::error_code ec;
  for (const auto& suite_dir : fs::directory_iterator(dir / "shards", ec)) {
    suite = suite_dir.path().filename().string();
    for (const auto& shard : fs::directory_iterator(suite_dir.path(), ec))
      if (fs::is_regular_file(shard.path() / "progress.jsonl") &&
          read_run_state(shard.path()).locked)
        throw InputError(shard.path().string(),
                         "this shard is still being written by a deepvox process (its task "
                         "still runs?); resume the session when it ended");
  }
  if (s.dry_run) {
    std::printf("# %s\n%s\n# %s\n%s", array.c_str(), script.c_str(), merge.c_str(),
                read_file_text(merge).c_str());
    return 0;
  }
  return submit_or_print(array, merge, o, s, tasks,
                         suite.empty() ? dir.parent_path().filename().string() : suite);
}

}  // namespace

SlurmScripts slurm_scripts(const SuiteOptions& o, const SlurmOptions& s, const std::string& folder,
                           const std::string& exe) {
  const std::string suite_path = fs::absolute(resolve_suite_path(o.suite)).string();
  const Suite suite = load_suite(suite_path);
  const std::string n = std::to_string(s.tasks);
  const fs::path dir = fs::absolute(folder);
  const std::string shards = (dir / "shards").string();
  std::string costs = fixed_cost_source(o, suite);
  if (costs != "estimate") costs = fs::absolute(costs).string();
  std::string shard_command = quoted(exe);
  for (const std::string& a : shard_arguments(o, suite_path, 0, s.tasks, shards, costs))
    shard_command += " " + (a == "0/" + n ? "\"$task/" + n + "\"" : quoted(a));
  // A task that starts again (requeued after preemption or a node failure, or by itself below)
  // resumes the newest folder of its shard; a task whose deepvox alone was killed requeues
  // itself, at most three times.
  const std::string shard_folders = quoted(shards + "/" + suite.name) + "/*-shard\"$task\"of" + n;
  SlurmScripts out{dir.string(), "", ""};
  out.array = header("deepvox-" + suite.name, s, (dir / "slurm" / "shard-%a.log").string()) +
              "#SBATCH --array=1-" + n + "\n" +
              (o.backend == "cpu" ? "#SBATCH --cpus-per-task=1\n" : "#SBATCH --gres=gpu:1\n") +
              "#SBATCH --requeue\n#SBATCH --open-mode=append\n# Shard i of " + n + " of suite " +
              suite.name + ". By hand: SLURM_ARRAY_TASK_ID=i bash " +
              (dir / "slurm" / "array.sbatch").string() +
              "\n# Requeue-safe: a restarted task resumes its shard's folder (deepvox suite "
              "--resume), and a task whose deepvox was killed requeues itself (at most 3 "
              "restarts).\nset -u\ntask=\"${SLURM_ARRAY_TASK_ID:?set SLURM_ARRAY_TASK_ID to 1.." +
              n + "}\"\ncd " + quoted(fs::current_path().string()) + "\nfolder=$(ls -d " +
              shard_folders + " " + shard_folders + "-* 2> /dev/null | tail -n 1)\n" +
              shard_command +
              " ${folder:+--resume \"$folder\"} && exit 0\nrc=$?\n"
              "if [ \"$rc\" -gt 128 ] && [ \"$rc\" -ne 130 ] && [ -n \"${SLURM_JOB_ID:-}\" ] &&\n"
              "   [ \"${SLURM_RESTART_COUNT:-0}\" -lt 3 ]; then\n"
              "  echo \"deepvox: shard $task ended by signal $((rc - 128)); requeueing it to "
              "resume\" >&2\n  scontrol requeue \"$SLURM_JOB_ID\"\nfi\nexit \"$rc\"\n";
  out.merge =
      header("deepvox-" + suite.name + "-merge", s, (dir / "slurm" / "merge.log").string()) +
      "# After every shard ended (afterany): merge what finished; the report names missing "
      "shards.\nset -eu\ncd " +
      quoted(fs::current_path().string()) + "\nexec " + quoted(exe) +
      " merge --allow-missing --out " + quoted(fs::absolute(o.out).string()) + " " +
      quoted(shards + "/" + suite.name) + "/*\n";
  return out;
}

int write_slurm_jobs(const SuiteOptions& o, const SlurmOptions& s) {
  if (o.resume) return resume_slurm_session(o, s);
  const Suite suite = load_suite(resolve_suite_path(o.suite));
  const std::string exe = fs::read_symlink("/proc/self/exe").string();
  const std::string sha = build_git_sha();
  if (s.dry_run) {
    const SlurmScripts scripts = slurm_scripts(
        o, s, (fs::path(o.out) / suite.name / run_folder_name(sha, "slurm")).string(), exe);
    std::printf("# %s/slurm/array.sbatch\n%s\n# %s/slurm/merge.sbatch\n%s", scripts.folder.c_str(),
                scripts.array.c_str(), scripts.folder.c_str(), scripts.merge.c_str());
    return 0;
  }
  const fs::path folder = make_run_folder(o.out, suite.name, sha, "slurm");
  const SlurmScripts scripts = slurm_scripts(o, s, folder.string(), exe);
  const fs::path dir = fs::path(scripts.folder) / "slurm";
  fs::create_directories(dir);
  const fs::path array = dir / "array.sbatch", merge = dir / "merge.sbatch";
  std::ofstream(array) << scripts.array;
  std::ofstream(merge) << scripts.merge;
  fs::permissions(array, fs::perms::owner_exec, fs::perm_options::add);
  fs::permissions(merge, fs::perms::owner_exec, fs::perm_options::add);
  return submit_or_print(array, merge, o, s, s.tasks, suite.name);
}

}  // namespace dv
