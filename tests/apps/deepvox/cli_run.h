// Runs the deepvox executable of this build (bin/deepvox beside the tests) with arguments and
// returns its exit code (128 + signal when it crashed) and its stdout and stderr together.
#pragma once

#include <sys/wait.h>

#include <cstdio>
#include <string>
#include "experiments/source_paths.h"

namespace dv {

struct CommandResult {
  int exit_code;
  std::string output;  // stdout and stderr
};

inline CommandResult run(const std::string& args) {
  const std::string cmd = test::binary_dir() + "/bin/deepvox " + args + " 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  std::string out;
  char buf[4096];
  while (size_t n = fread(buf, 1, sizeof buf, pipe)) out.append(buf, n);
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status), out};
}

}  // namespace dv
