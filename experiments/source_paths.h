// Where tests and benchmarks find the repository's files: $DEEPVOX_SOURCE_DIR when set (a
// build carried to another machine), else the source tree the binary was built from; and the
// names of tests parameterised over scene files.
#pragma once

#include <cctype>
#include <cstdlib>
#include <string>

namespace dv::test {

inline std::string source_dir() {
  const char* env = std::getenv("DEEPVOX_SOURCE_DIR");
  return env && *env ? env : DEEPVOX_SOURCE_DIR;
}

// Readable names for tests parameterised over scene files: "knecht-fig56.json" -> knecht_fig56.
struct SceneFileName {
  template <class Info>
  std::string operator()(const Info& info) const {
    std::string n = info.param;
    n = n.substr(0, n.find('.'));
    for (char& ch : n) ch = std::isalnum(static_cast<unsigned char>(ch)) ? ch : '_';
    return n;
  }
};

}  // namespace dv::test
