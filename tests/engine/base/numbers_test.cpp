// Numbers as a person types them (engine/base/numbers.h): decimals and fractions, nothing else;
// and lengths and durations as a person reads them.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "engine/base/error.h"
#include "engine/base/numbers.h"
#include "engine/synthesize/mix_palette.h"

using namespace mostyle;

TEST_CASE("parse_number: decimals and fractions") {
  double v = 0.0;
  CHECK(parse_number("0.25", &v));
  CHECK(v == 0.25);
  CHECK(parse_number("-1e-3", &v));
  CHECK(v == -1e-3);
  CHECK(parse_number("1/3", &v));
  CHECK(v == 1.0 / 3.0);
  CHECK(parse_number("-2/3", &v));
  CHECK(v == -2.0 / 3.0);
  CHECK(parse_number("1.5/0.5", &v));
  CHECK(v == 3.0);
  for (const char* bad : {"", " 1", "1 ", "a", "1/", "/3", "1/0", "1/3/4", "1//3", "inf", "nan", "1e400", "0x", "1,2"}) {
    INFO(bad);
    CHECK_FALSE(parse_number(bad, &v));
  }
}

TEST_CASE("normalized_weights: a sum within 0.001 of 1 is divided out, anything else is left for Validate") {
  const std::vector<double> six(6, 0.166667);  // sums to 1.000002
  const std::vector<double> w = normalized_weights(six);
  double sum = 0.0;
  for (double x : w) sum += x;
  CHECK(sum == Approx(1.0).margin(1e-15));
  MixParams mp;
  mp.layers = take_layers(w);
  CHECK_NOTHROW(mp.Validate(6, 0));
  const std::vector<double> exact = {0.25, 0.75};
  CHECK(normalized_weights(exact) == exact);
  const std::vector<double> off = {0.5, 0.6};  // 1.1: refused by Validate, not normalized
  CHECK(normalized_weights(off) == off);
  mp.layers = take_layers(normalized_weights(off));
  CHECK_THROWS_AS(mp.Validate(2, 0), InputError);
}

TEST_CASE("to_float32: the nearest float, infinity beyond float's range", "[numbers]") {
  CHECK(mostyle::to_float32(0.1) == 0.1f);
  CHECK(mostyle::to_float32(1e300) == std::numeric_limits<float>::infinity());
  CHECK(mostyle::to_float32(-1e300) == -std::numeric_limits<float>::infinity());
  CHECK(std::isnan(mostyle::to_float32(std::nan(""))));
}

TEST_CASE("length_in_words: metric units from the file's unit, else a share of the height") {
  CHECK(length_in_words(1.5, 1.0, 170.0) == "1.5 cm");
  CHECK(length_in_words(0.25, 1.0, 170.0, "/s") == "2.5 mm/s");
  CHECK(length_in_words(1.5, 100.0, 1.7) == "1.50 m");
  CHECK(length_in_words(0.5, 0.0, 25.0) == "2% of height");
  CHECK(length_in_words(0.5, 0.0, 0.0) == "-");
  CHECK(length_in_words(-1.0, 1.0, 170.0) == "-");
}

TEST_CASE("duration_in_words: hundredths of a second, one way everywhere") {
  CHECK(duration_in_words(6.466660200000001) == "6.47 s");
  CHECK(duration_in_words(1.1) == "1.10 s");
  CHECK(duration_in_words(0.0) == "0.00 s");
  CHECK(duration_in_words(120.0) == "120.00 s");
  CHECK(duration_in_words(NAN) == "-");
}
