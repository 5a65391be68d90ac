#include "engine/base/memory_limit.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>

#include "engine/base/error.h"

namespace mostyle {

size_t parse_memory_limit(std::string_view value) {
  if (value.empty()) return kDefaultMaxBytes;
  constexpr size_t kMaxMegabytes = SIZE_MAX >> 20;
  size_t megabytes = 0;
  const auto r = std::from_chars(value.data(), value.data() + value.size(), megabytes);
  if (r.ec != std::errc() || r.ptr != value.data() + value.size() || megabytes == 0 || megabytes > kMaxMegabytes) {
    throw InputError(std::string(kMemoryLimitVariable) + ": expected a whole number of megabytes from 1 up, found '" +
                     std::string(value.substr(0, 40)) + "'");
  }
  return megabytes << 20;
}

std::string describe_bytes(size_t bytes) {
  if (bytes < 1024) return std::to_string(bytes) + (bytes == 1 ? " byte" : " bytes");
  static const char* const kUnits[] = {"KB", "MB", "GB", "TB", "PB", "EB"};
  double value = static_cast<double>(bytes) / 1024;
  int unit = 0;
  while (value >= 1024 && unit < 5) {
    value /= 1024;
    ++unit;
  }
  char buffer[32];
  // Tenths, rounded up: an amount over a limit never reads as less than the limit.
  const double tenths = std::ceil(value * 10 - 1e-9);
  if (static_cast<long long>(tenths) % 10 == 0)
    std::snprintf(buffer, sizeof buffer, "%lld %s", static_cast<long long>(tenths / 10), kUnits[unit]);
  else
    std::snprintf(buffer, sizeof buffer, "%.1f %s", tenths / 10, kUnits[unit]);
  return buffer;
}

}  // namespace mostyle
