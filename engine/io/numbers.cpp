#include "engine/io/numbers.h"

#include <cctype>
#include <cmath>
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

}  // namespace mostyle
