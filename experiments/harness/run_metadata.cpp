// Run metadata for stats and result files (see run_metadata.h).
#include "experiments/harness/run_metadata.h"

#include <sys/utsname.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <optional>
#include <sstream>

#include "core/parallel.h"
#include "cuda/device_memory.h"

#include "git_sha.h"
#ifndef DEEPVOX_BUILD_TYPE
#define DEEPVOX_BUILD_TYPE "unknown"
#endif

namespace dv {

namespace {

std::string g_command_line;

// `git rev-parse` in the working directory, when git and a repository are there.
std::string runtime_git_sha() {
  FILE* pipe = popen("git rev-parse --short=12 HEAD 2>/dev/null", "r");
  if (!pipe) return "";
  char buf[64] = {0};
  std::string sha = fgets(buf, sizeof buf, pipe) ? buf : "";
  pclose(pipe);
  while (!sha.empty() && (sha.back() == '\n' || sha.back() == '\r')) sha.pop_back();
  return sha;
}

// A command's standard output; nothing when it cannot run or exits other than with 0.
std::optional<std::string> command_output(const std::string& command) {
  FILE* pipe = popen((command + " 2>/dev/null").c_str(), "r");
  if (!pipe) return std::nullopt;
  std::string out;
  char buf[512];
  while (size_t n = fread(buf, 1, sizeof buf, pipe)) out.append(buf, n);
  if (pclose(pipe) != 0) return std::nullopt;
  return out;
}

std::string file_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string trimmed(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t\r\n\"'");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t\r\n\"'") - a + 1);
}

std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream in(line);
  for (std::string f; std::getline(in, f, ',');) fields.push_back(trimmed(f));
  return fields;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::stringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (!trimmed(line).empty()) lines.push_back(line);
  return lines;
}

// "1980 MHz" as the number 1980; anything else ("[N/A]") as "unknown".
nlohmann::json megahertz(const std::string& field) {
  char* end = nullptr;
  const long v = std::strtol(field.c_str(), &end, 10);
  if (end == field.c_str() || trimmed(end) != "MHz") return "unknown";
  return v;
}

nlohmann::json known(const std::string& field) {
  return field.empty() || field.front() == '[' ? nlohmann::json("unknown") : nlohmann::json(field);
}

// The line of the GPU CUDA uses first (see machine_state), or -1.
int cuda_gpu_line(const std::vector<nlohmann::json>& gpus) {
  std::string first;
  if (const char* visible = std::getenv("CUDA_VISIBLE_DEVICES"))
    first = trimmed(std::string(visible).substr(0, std::string(visible).find(',')));
  for (size_t i = 0; i < gpus.size(); ++i) {
    const std::string index = gpus[i]["gpu_index"].is_string()
                                  ? gpus[i]["gpu_index"].get<std::string>()
                                  : std::to_string(gpus[i]["gpu_index"].get<long>());
    const std::string uuid = gpus[i]["gpu_uuid"].get<std::string>();
    if (first.empty() ? index == "0" : first == index || uuid.rfind(first, 0) == 0) return int(i);
  }
  return -1;
}

std::string kernel_name() {
  utsname u;
  if (uname(&u) != 0) return "unknown";
  return std::string(u.sysname) + " " + u.release + " " + u.machine;
}

}  // namespace

nlohmann::json parse_nvidia_smi_gpu(const std::string& csv_line) {
  std::vector<std::string> f = csv_fields(csv_line);
  f.resize(9);
  nlohmann::json index = known(f[0]);
  if (index.is_string() && index != "unknown") {
    char* end = nullptr;
    const long i = std::strtol(f[0].c_str(), &end, 10);
    if (*end == '\0') index = i;
  }
  return {{"gpu_index", index},
          {"gpu_uuid", known(f[1])},
          {"nvidia_driver", known(f[2])},
          {"sm_clock_mhz", megahertz(f[3])},
          {"sm_clock_max_mhz", megahertz(f[4])},
          {"memory_clock_mhz", megahertz(f[5])},
          {"memory_clock_max_mhz", megahertz(f[6])},
          {"persistence_mode", known(f[7])},
          {"compute_mode", known(f[8])}};
}

std::string driver_from_proc_version(const std::string& text) {
  const std::string first = text.substr(0, text.find('\n'));
  const size_t module = first.find("Kernel Module");
  if (module == std::string::npos) return "unknown";
  std::stringstream rest(first.substr(module + 13));
  std::string version;
  rest >> version;
  return version.empty() ? "unknown" : version;
}

std::string os_pretty_name(const std::string& os_release_text) {
  for (const std::string& line : lines_of(os_release_text))
    if (line.rfind("PRETTY_NAME=", 0) == 0) {
      const std::string name = trimmed(line.substr(12));
      return name.empty() ? "unknown" : name;
    }
  return "unknown";
}

nlohmann::json machine_state(const MachineSources& sources) {
  nlohmann::json m = parse_nvidia_smi_gpu("");
  m["driver_source"] = "none";
  m["gpu_shared"] = "unknown";
  const std::string smi = "'" + sources.nvidia_smi + "'";
  std::vector<nlohmann::json> gpus;
  for (const std::string& line : lines_of(
           command_output(smi + " --query-gpu=index,uuid,driver_version,clocks.sm,clocks.max.sm,"
                                "clocks.mem,clocks.max.mem,persistence_mode,compute_mode "
                                "--format=csv,noheader")
               .value_or("")))
    gpus.push_back(parse_nvidia_smi_gpu(line));
  const int line = cuda_gpu_line(gpus);
  if (line >= 0) {
    m.update(gpus[size_t(line)]);
    m["driver_source"] = "nvidia-smi";
    const std::string uuid = m["gpu_uuid"].is_string() ? m["gpu_uuid"].get<std::string>() : "";
    const std::optional<std::string> apps =
        command_output(smi + " --query-compute-apps=gpu_uuid,pid --format=csv,noheader");
    if (apps && uuid != "unknown") {
      int others = 0;
      for (const std::string& app : lines_of(*apps)) {
        const std::vector<std::string> f = csv_fields(app);
        others += f.size() >= 2 && f[0] == uuid && f[1] != std::to_string(getpid());
      }
      m["gpu_shared"] =
          others == 0 ? "no" : "yes: " + std::to_string(others) + " other compute processes";
    }
  }
  if (m["nvidia_driver"] == "unknown") {
    const std::string proc = driver_from_proc_version(file_text(sources.nvidia_proc_version));
    if (proc != "unknown") {
      m["nvidia_driver"] = proc;
      m["driver_source"] = sources.nvidia_proc_version;
    }
  }
  m["os"] = os_pretty_name(file_text(sources.os_release));
  m["kernel"] = kernel_name();
  return m;
}

std::string host_name() {
  char name[256] = {0};
  return gethostname(name, sizeof name - 1) == 0 && name[0] ? name : "unknown";
}

void remember_command_line(int argc, char** argv) {
  g_command_line.clear();
  for (int i = 0; i < argc; ++i) g_command_line += (i ? " " : "") + std::string(argv[i]);
}

const std::string& command_line() {
  return g_command_line;
}

std::string build_git_sha() {
  return DEEPVOX_GIT_SHA;
}

std::string version_text() {
  return std::string("deepvox ") + DEEPVOX_VERSION + "\ncommit " + build_git_sha() + "\nbuild " +
         DEEPVOX_BUILD_TYPE + ", " + __VERSION__ + ", CUDA " + (kBuiltWithCuda ? "yes" : "no");
}

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("model name", 0) != 0) continue;
    const size_t colon = line.find(':');
    if (colon != std::string::npos) return line.substr(line.find_first_not_of(' ', colon + 1));
  }
  return "unknown";
}

std::string utc_time_now() {
  char when[32];
  const std::time_t now = std::time(nullptr);
  std::strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  return when;
}

nlohmann::json run_metadata(Backend backend) {
  const std::string when = utc_time_now();
  const std::string sha = build_git_sha();
  nlohmann::json m = {{"deepvox_version", DEEPVOX_VERSION},
                      {"git_sha", sha},
                      {"git_dirty", sha.find("-dirty") != std::string::npos},
                      {"git_sha_at_run", runtime_git_sha()},
                      {"build_type", DEEPVOX_BUILD_TYPE},
                      {"compiler", __VERSION__},
                      {"cuda_built", kBuiltWithCuda},
                      {"backend", to_string(backend)},
                      {"host", host_name()},
                      {"cpu_model", cpu_model()},
                      {"cpu_threads", cpu_thread_count()},
                      {"command_line", g_command_line},
                      {"utc_time", when},
                      {"machine", machine_state()}};
  if (const char* visible = std::getenv("CUDA_VISIBLE_DEVICES"))
    m["cuda_visible_devices"] = visible;
  if (cuda_device_available()) {
    const CudaDeviceInfo info = cuda_device_info();
    m["device"] = info.name;
    m["cuda"] = {{"runtime_version", info.runtime_version},
                 {"driver_api_version", info.driver_version},
                 {"sm_clock_max_mhz", info.sm_clock_max_mhz},
                 {"memory_clock_max_mhz", info.memory_clock_max_mhz},
                 {"multiprocessors", info.multiprocessors},
                 {"memory_bytes", info.memory_bytes}};
  }
  return m;
}

}  // namespace dv
