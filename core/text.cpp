// Text helpers (see text.h).
#include "core/text.h"

#include <cctype>
#include <filesystem>

namespace dv {

std::string lowercase(std::string text) {
  for (char& c : text) c = char(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

std::string lowercase_extension(const std::string& path) {
  return lowercase(std::filesystem::path(path).extension().string());
}

}  // namespace dv
