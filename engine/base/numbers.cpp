#include "engine/base/numbers.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

namespace mostyle {
namespace {

bool parse_decimal(const std::string& text, double* value) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text[0]))) return false;
  char* end = nullptr;
  *value = std::strtod(text.c_str(), &end);
  return *end == '\0' && std::isfinite(*value);
}

}  // namespace

bool parse_number(const std::string& text, double* value) {
  const size_t slash = text.find('/');
  if (slash == std::string::npos) return parse_decimal(text, value);
  double numerator = 0.0, denominator = 0.0;
  if (!parse_decimal(text.substr(0, slash), &numerator) || !parse_decimal(text.substr(slash + 1), &denominator) ||
      denominator == 0.0)
    return false;
  *value = numerator / denominator;
  return std::isfinite(*value);
}

float to_float32(double value) {
  constexpr double kMax = std::numeric_limits<float>::max();
  if (value > kMax) return std::numeric_limits<float>::infinity();
  if (value < -kMax) return -std::numeric_limits<float>::infinity();
  return static_cast<float>(value);  // NaN stays NaN
}

std::string length_in_words(double value, double cm_per_unit, double height, const char* per) {
  char text[48];
  if (!std::isfinite(value) || value < 0.0) return "-";
  if (cm_per_unit > 0.0) {
    const double cm = value * cm_per_unit;
    if (cm >= 100.0) std::snprintf(text, sizeof text, "%.2f m%s", cm / 100.0, per);
    else if (cm >= 1.0) std::snprintf(text, sizeof text, "%.1f cm%s", cm, per);
    else std::snprintf(text, sizeof text, "%.1f mm%s", 10.0 * cm, per);
  } else if (height > 0.0) {
    std::snprintf(text, sizeof text, "%.2g%% of height%s", 100.0 * value / height, per);
  } else {
    return "-";
  }
  return text;
}

std::string duration_in_words(double seconds) {
  if (!std::isfinite(seconds)) return "-";
  char text[48];
  std::snprintf(text, sizeof text, "%.2f s", seconds);
  return text;
}

}  // namespace mostyle
