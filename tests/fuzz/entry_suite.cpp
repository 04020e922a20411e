// Fuzz entry: the suite-file parser, then the expansion of its sweeps into runs
// (fuzz_entry.h).
#include "core/error.h"
#include "experiments/harness/suite_file.h"
#include "tests/fuzz/fuzz_entry.h"

namespace dv::fuzz {

int suite(const uint8_t* data, size_t size) {
  try {
    const Suite s =
        parse_suite(std::string(reinterpret_cast<const char*>(data), size), "fuzz.json");
    expand_suite(s);
  } catch (const InputError&) {
  }
  return 0;
}

}  // namespace dv::fuzz
