// Run metadata for stats and result files (see run_metadata.h).
#include "experiments/harness/run_metadata.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>

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

}  // namespace

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

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("model name", 0) != 0) continue;
    const size_t colon = line.find(':');
    if (colon != std::string::npos) return line.substr(line.find_first_not_of(' ', colon + 1));
  }
  return "unknown";
}

nlohmann::json run_metadata(Backend backend) {
  char when[32];
  const std::time_t now = std::time(nullptr);
  std::strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
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
                      {"utc_time", when}};
  if (const char* visible = std::getenv("CUDA_VISIBLE_DEVICES"))
    m["cuda_visible_devices"] = visible;
  if (cuda_device_available()) {
    const CudaDeviceInfo info = cuda_device_info();
    m["device"] = info.name;
    m["cuda"] = {{"runtime_version", info.runtime_version},
                 {"driver_version", info.driver_version},
                 {"sm_clock_max_mhz", info.sm_clock_max_mhz},
                 {"memory_clock_max_mhz", info.memory_clock_max_mhz},
                 {"multiprocessors", info.multiprocessors},
                 {"memory_bytes", info.memory_bytes}};
  }
  return m;
}

}  // namespace dv
