// Where tests and benchmarks find the repository's files: $DEEPVOX_SOURCE_DIR when set (a
// build carried to another machine), else the source tree the binary was built from.
#pragma once

#include <cstdlib>
#include <string>

namespace dv::test {

inline std::string source_dir() {
  const char* env = std::getenv("DEEPVOX_SOURCE_DIR");
  return env && *env ? env : DEEPVOX_SOURCE_DIR;
}

}  // namespace dv::test
