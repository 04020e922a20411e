// Shadow methods for tests, created by registered name from "key=value key=value" parameters,
// as `--param` gives them on the command line.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "strategies/shadow/shadow_method.h"

namespace dv::test {

inline std::unique_ptr<ShadowMethod> make_shadow_method(const std::string& name,
                                                        const std::string& params) {
  std::vector<std::string> items;
  for (size_t start = 0; start < params.size();) {
    size_t end = params.find(' ', start);
    if (end == std::string::npos) end = params.size();
    if (end > start) items.push_back(params.substr(start, end - start));
    start = end + 1;
  }
  return shadow_registry().create(name, StrategyParams::parse(items));
}

}  // namespace dv::test
