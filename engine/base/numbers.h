#pragma once
// Numbers as a person types them on a command line or in a field, and as a person reads them.
#include <string>

namespace mostyle {

// A decimal ("0.25", "-1e-3") or a fraction ("1/3", "-2/3"), nothing else around it. false on
// anything else, a zero denominator or a value that is not finite; *value is then unspecified.
bool parse_number(const std::string& text, double* value);

// `value` as a float32, as files store numbers: the nearest float, and +-infinity beyond float's
// range (where a plain cast is undefined) and NaN for NaN.
float to_float32(double value);

// A length (or speed, with per = "/s") of `value` file units in words: "1.5 cm", "4.2 mm",
// "1.23 m", or, when cm_per_unit is 0, "2.1% of height" of a skeleton `height` units tall
// ("-" when neither is known, or for a negative or non-finite value). cm_per_unit: from
// kinematics/units.h centimetres_per_unit.
std::string length_in_words(double value, double cm_per_unit, double height, const char* per = "");

// A duration for a person, to a hundredth of a second: "6.47 s" ("-" when not finite). Every
// length of a motion the programs print (summaries, info, the editor's export) says it so.
std::string duration_in_words(double seconds);

}  // namespace mostyle
