#include "engine/io/memory_limit.h"

#include <cmath>
#include <cstdio>

namespace mostyle {

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
