#pragma once
// Numbers as a person types them on a command line or in a field.
#include <string>

namespace mostyle {

// A decimal ("0.25", "-1e-3") or a fraction ("1/3", "-2/3"), nothing else around it. false on
// anything else, a zero denominator or a value that is not finite; *value is then unspecified.
bool parse_number(const std::string& text, double* value);

// `value` as a float32, as files store numbers: the nearest float, and +-infinity beyond float's
// range (where a plain cast is undefined) and NaN for NaN.
float to_float32(double value);

}  // namespace mostyle
