// Where tests and benchmarks find the repository's files: $DEEPVOX_SOURCE_DIR when set (a
// build carried to another machine), else the source tree the binary was built from; the build
// tree they write scratch files and find bin/deepvox in; and the names of tests parameterised
// over scene files. The two folders are compiled into source_paths.cpp alone, so no other file's
// object depends on where the tree lies (a compiler cache serves any clone).
#pragma once

#include <cctype>
#include <string>

namespace dv::test {

std::string source_dir();
std::string binary_dir();

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
