// The scratch input file of the fuzz entry points (fuzz_entry.h).
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "tests/fuzz/fuzz_entry.h"

namespace dv::fuzz {

std::string scratch_input(const uint8_t* data, size_t size, const std::string& ext) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("deepvox-fuzz-" + std::to_string(getpid()) + ext);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
  return path.string();
}

}  // namespace dv::fuzz
