// Reservation checks (see memory_check.h).
#include "cuda/memory_check.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>

#include "core/error.h"

namespace dv {

namespace {

int64_t host_available_bytes() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key, unit;
  int64_t kib = 0;
  while (meminfo >> key >> kib >> unit)
    if (key == "MemAvailable:") return kib * 1024;
  return std::numeric_limits<int64_t>::max();  // unknown: let the allocator decide
}

}  // namespace

int64_t free_memory_bytes(Memory memory) {
  int64_t free = memory == Memory::device ? int64_t(device_free_bytes()) : host_available_bytes();
  if (const char* limit = std::getenv("DEEPVOX_MEMORY_LIMIT"))
    free = std::min<int64_t>(free, std::strtoll(limit, nullptr, 10));
  return free;
}

std::string format_bytes(int64_t bytes) {
  const char* units[] = {"B", "kB", "MB", "GB", "TB"};
  double value = double(bytes);
  int u = 0;
  while (value >= 1000.0 && u < 4) value /= 1000.0, ++u;
  char text[32];
  std::snprintf(text, sizeof text, u ? "%.3g %s" : "%.0f %s", value, units[u]);
  return text;
}

void check_reservation(Memory memory, int64_t bytes, const std::string& what) {
  if (bytes <= 0) return;
  const int64_t free = free_memory_bytes(memory);
  if (bytes > free)
    throw OutOfMemory(what,
                      format_bytes(bytes) + " (" + std::to_string(bytes) + " bytes) asked, " +
                          format_bytes(free) + " free on the " +
                          (memory == Memory::device ? "device" : "host") +
                          "; lower the map resolution or the storage's limits",
                      bytes);
}

}  // namespace dv
