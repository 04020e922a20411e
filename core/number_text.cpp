// Numbers as text (see number_text.h).
#include "core/number_text.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace dv {

std::string significant_text(double value, int digits) {
  char text[48];
  std::snprintf(text, sizeof text, "%.*g", digits, value);
  return text;
}

std::string fixed_text(double value, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

std::string signed_text(double value, int digits) {
  return (value >= 0 ? "+" : "") + significant_text(value, digits);
}

std::string table_text(double value, int digits) {
  if (std::isfinite(value) && value == std::floor(value) && std::abs(value) < 1e15) {
    char text[48];
    std::snprintf(text, sizeof text, "%.0f", value);
    return text;
  }
  return significant_text(value, digits);
}

std::string exact_text(double value) {
  char text[48];
  for (int digits = 6; digits <= 17; ++digits) {
    std::snprintf(text, sizeof text, "%.*g", digits, value);
    if (std::strtod(text, nullptr) == value) break;
  }
  return text;
}

std::string exact_text(float value) {
  char text[48];
  const auto end = std::to_chars(text, text + sizeof text, value).ptr;
  return std::string(text, end);
}

}  // namespace dv
