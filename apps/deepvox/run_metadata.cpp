// Run metadata for stats and result files (see run_metadata.h).
#include "apps/deepvox/run_metadata.h"

#include <ctime>

#include "core/device_memory.h"
#include "core/parallel.h"

#include "git_sha.h"
#ifndef DEEPVOX_BUILD_TYPE
#define DEEPVOX_BUILD_TYPE "unknown"
#endif

namespace dv::cli {

namespace {
std::string g_command_line;
}

void remember_command_line(int argc, char** argv) {
  g_command_line.clear();
  for (int i = 0; i < argc; ++i) g_command_line += (i ? " " : "") + std::string(argv[i]);
}

nlohmann::json run_metadata(Backend backend) {
  char when[32];
  const std::time_t now = std::time(nullptr);
  std::strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  nlohmann::json m = {{"deepvox_version", DEEPVOX_VERSION},
                      {"git_sha", DEEPVOX_GIT_SHA},
                      {"build_type", DEEPVOX_BUILD_TYPE},
                      {"compiler", __VERSION__},
                      {"cuda_built", kBuiltWithCuda},
                      {"backend", to_string(backend)},
                      {"cpu_threads", cpu_thread_count()},
                      {"command_line", g_command_line},
                      {"utc_time", when}};
  if (backend == Backend::cuda) m["device"] = cuda_device_name();
  return m;
}

}  // namespace dv::cli
