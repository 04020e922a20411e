// libFuzzer's entry for one fuzz target: DEEPVOX_FUZZ_ENTRY names the function of
// fuzz_entry.h it runs (set per executable in CMakeLists.txt).
#include "tests/fuzz/fuzz_entry.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return dv::fuzz::DEEPVOX_FUZZ_ENTRY(data, size);
}
