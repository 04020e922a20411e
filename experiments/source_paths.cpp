// The source and build folders of experiments/source_paths.h, the one file compiled with them.
#include "experiments/source_paths.h"

#include <cstdlib>

namespace dv::test {

std::string source_dir() {
  const char* env = std::getenv("DEEPVOX_SOURCE_DIR");
  return env && *env ? env : DEEPVOX_SOURCE_DIR;
}

std::string binary_dir() {
  return DEEPVOX_BINARY_DIR;
}

}  // namespace dv::test
