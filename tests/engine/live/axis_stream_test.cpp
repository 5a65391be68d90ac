// Axis Neuron's BVH broadcasting lines: hand-worked lines parsed and written, every reason a line
// is refused, the round trip within the written precision, and the splitter against every way a
// stream's bytes may be cut into chunks.
#include "engine/live/axis_stream.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <string>
#include <vector>

using namespace mostyle;

namespace {

// Written values read back within this of the value, relative (7 significant digits: 5e-7).
constexpr double kRoundTrip = 1e-6;

AxisFrame parsed(const std::string& line, int channels) {
  AxisFrame f;
  std::string reason;
  const AxisLineStatus s = parse_axis_line(line, channels, &f, &reason);
  INFO(reason);
  REQUIRE(s == AxisLineStatus::kOk);
  return f;
}

std::string refusal(const std::string& line, int channels) {
  AxisFrame f;
  std::string reason;
  REQUIRE(parse_axis_line(line, channels, &f, &reason) == AxisLineStatus::kMalformed);
  return reason;
}

// Every line the splitter gives for `chunks`, fed one after another.
std::vector<std::string> split(AxisLineSplitter& s, const std::vector<std::string>& chunks,
                               std::vector<long long>* numbers = nullptr) {
  std::vector<std::string> lines;
  for (const std::string& c : chunks) {
    std::string_view rest = c, line;
    while (s.next(&rest, &line)) {
      lines.emplace_back(line);
      if (numbers) numbers->push_back(s.line_number());
    }
    CHECK(rest.empty());
  }
  return lines;
}

}  // namespace

TEST_CASE("axis line: index, name and values, as Axis writes them", "[axis]") {
  const AxisFrame f = parsed("0 Avatar00 1.5 -2 0.000125 ||", 3);
  CHECK(f.avatar_index == 0);
  CHECK(f.avatar_name == "Avatar00");
  CHECK(f.values == std::vector<double>{1.5, -2.0, 0.000125});
  CHECK(f.reference.empty());
}

TEST_CASE("axis line: whitespace, CR, '||' touching the last value, '+' and exponents are tolerated", "[axis]") {
  const AxisFrame f = parsed("  12\tBob_1   +4 5e-1\t-6E2||  \r", 3);
  CHECK(f.avatar_index == 12);
  CHECK(f.avatar_name == "Bob_1");
  CHECK(f.values == std::vector<double>{4.0, 0.5, -600.0});
}

TEST_CASE("axis line: N + 6 values are a reference first, then the channels", "[axis]") {
  const AxisFrame f = parsed("1 A 10 20 30 1 2 3 7 8 9 ||", 3);
  CHECK(f.reference == std::vector<double>{10, 20, 30, 1, 2, 3});
  CHECK(f.values == std::vector<double>{7, 8, 9});
  // The vectors are reused: a line without a reference after one with it has none.
  AxisFrame g = f;
  std::string reason;
  REQUIRE(parse_axis_line("1 A 4 5 6 ||", 3, &g, &reason) == AxisLineStatus::kOk);
  CHECK(g.reference.empty());
  CHECK(g.values == std::vector<double>{4, 5, 6});
}

TEST_CASE("axis line: every reason a line is not a frame", "[axis]") {
  CHECK(refusal("0 A 1 2 3", 3) == "the line does not end in '||'");
  CHECK(refusal("0 A 1 2 3 |", 3) == "the line does not end in '||'");
  CHECK(refusal("0 A 1 2 ||", 3) == "expected 3 values (9 with a reference), found 2");
  CHECK(refusal("0 A 1 2 3 4 ||", 3) == "expected 3 values (9 with a reference), found 4");
  CHECK(refusal("0 A 1 x 3 ||", 3) == "value 2 is not a number: 'x'");
  CHECK(refusal("0 A 1 2 3- ||", 3) == "value 3 is not a number: '3-'");
  CHECK(refusal("0 A 1 2 ++3 ||", 3) == "value 3 is not a number: '++3'");
  CHECK(refusal("0 A 1 2 || 3 ||", 3) == "value 3 is not a number: '||'");
  CHECK(refusal("0 A nan 2 3 ||", 3) == "value 1 is not a finite number: 'nan'");
  CHECK(refusal("0 A 1 -inf 3 ||", 3) == "value 2 is not a finite number: '-inf'");
  CHECK(refusal("0 A 1 2 1e999 ||", 3) == "value 3 is not a finite number: '1e999'");
  CHECK(refusal("A 1 2 3 ||", 3) == "expected an avatar index, found 'A'");
  CHECK(refusal("1.5 A 1 2 3 ||", 3) == "expected an avatar index, found '1.5'");
  CHECK(refusal("||", 3) == "expected an avatar index, found '||'");
  CHECK(refusal("0 ||", 3) == "expected an avatar name after the avatar index");
  // Bytes a terminal would act on are shown as '?'; long tokens are cut.
  CHECK(refusal("0 A 1 \x1b[2J 3 ||", 3) == "value 2 is not a number: '?[2J'");
  CHECK(refusal("0 A 1 " + std::string(40, 'z') + " 3 ||", 3) ==
        "value 2 is not a number: '" + std::string(24, 'z') + "...'");
  AxisFrame f;
  std::string reason;
  CHECK(parse_axis_line(" \t\r", 3, &f, &reason) == AxisLineStatus::kBlank);
  CHECK(parse_axis_line("", 3, &f, &reason) == AxisLineStatus::kBlank);
}

TEST_CASE("axis line written: 7 significant digits, the reference exact, Axis's layout", "[axis]") {
  std::string out;
  const double values[] = {1.0, 2.5, -0.000123456789, 12345678.9, 0.0, 179.123456};
  append_axis_line(&out, 0, "Avatar00", nullptr, 0, values, 6);
  CHECK(out == "0 Avatar00 1 2.5 -0.0001234568 1.234568e+07 0 179.1235 ||\n");
  out.clear();
  const double reference[] = {0.1, 1.0 / 3.0, -2, 0, 0, 90};
  append_axis_line(&out, 3, "B", reference, 6, values, 1);
  CHECK(out == "3 B 0.1 0.3333333333333333 -2 0 0 90 1 ||\n");
  // What is written reads back, the reference bit for bit.
  const AxisFrame f = parsed(out.substr(0, out.size() - 1), 1);
  CHECK(f.avatar_index == 3);
  CHECK(f.reference == std::vector<double>(reference, reference + 6));
}

TEST_CASE("axis line round trip: random values within 1e-6 of themselves", "[axis]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-8, 8);
  std::vector<double> values(354);
  for (int trial = 0; trial < 200; ++trial) {
    for (double& v : values) v = mantissa(rng) * std::pow(10.0, exponent(rng));
    std::string out;
    append_axis_line(&out, trial, "Avatar00", nullptr, 0, values.data(), static_cast<int>(values.size()));
    const AxisFrame f = parsed(out, static_cast<int>(values.size()));
    for (size_t i = 0; i < values.size(); ++i)
      REQUIRE(std::abs(f.values[i] - values[i]) <= kRoundTrip * std::abs(values[i]));
  }
}

TEST_CASE("axis splitter: the same lines however the bytes are cut", "[axis]") {
  // LF, CRLF, "||" with no line end after it, a blank line, a "||" across a cut.
  const std::string stream = "0 A 1 ||\n0 A 2 ||\r\n0 A 3 ||0 A 4 ||\n\n  \r\n0 A 5 ||";
  const std::vector<std::string> expected{"0 A 1 ||", "0 A 2 ||", "0 A 3 ||", "0 A 4 ||", "0 A 5 ||"};
  const std::vector<long long> expected_numbers{1, 2, 3, 3, 6};
  for (size_t cut = 0; cut <= stream.size(); ++cut) {
    for (size_t second = cut; second <= stream.size(); ++second) {
      AxisLineSplitter s;
      std::vector<long long> numbers;
      const auto lines =
          split(s, {stream.substr(0, cut), stream.substr(cut, second - cut), stream.substr(second)}, &numbers);
      INFO("cut at " << cut << " and " << second);
      CHECK(lines == expected);
      CHECK(numbers == expected_numbers);
      CHECK_FALSE(s.has_partial());
    }
  }
  // Byte by byte.
  AxisLineSplitter s;
  std::vector<std::string> bytes;
  for (char c : stream) bytes.emplace_back(1, c);
  CHECK(split(s, bytes) == expected);
}

TEST_CASE("axis splitter: a line without its end is held until it comes, then reset forgets it", "[axis]") {
  AxisLineSplitter s;
  CHECK(split(s, {"0 A 1 || 0 A 2"}).size() == 1);
  CHECK(s.has_partial());
  CHECK(split(s, {" ||"}) == std::vector<std::string>{" 0 A 2 ||"});
  CHECK(split(s, {"0 A 3"}).empty());
  s.reset();
  CHECK_FALSE(s.has_partial());
  CHECK(split(s, {" 9 ||\n"}) == std::vector<std::string>{" 9 ||"});
}

TEST_CASE("axis splitter: an over-long line is dropped and counted, the next ones kept", "[axis]") {
  const size_t max = 100;
  const std::string good = "0 A 1 ||\n";
  const std::string long_line = "0 A " + std::string(max, '7') + " ||\n";
  for (size_t chunk : {size_t{1}, size_t{7}, size_t{64}, size_t{1000}}) {
    AxisLineSplitter s(max);
    const std::string stream = good + long_line + good + long_line + long_line + good;
    std::vector<std::string> chunks;
    for (size_t at = 0; at < stream.size(); at += chunk) chunks.push_back(stream.substr(at, chunk));
    std::vector<long long> numbers;
    INFO("chunks of " << chunk);
    CHECK(split(s, chunks, &numbers) == std::vector<std::string>(3, "0 A 1 ||"));
    CHECK(numbers == std::vector<long long>{1, 3, 6});
    CHECK(s.dropped() == 3);
    CHECK(s.dropped_line_number() == 5);
  }
  // A line exactly max bytes long (its end aside) is kept.
  AxisLineSplitter s(8);
  CHECK(split(s, {"0 A 1 ||\n"}) == std::vector<std::string>{"0 A 1 ||"});
  CHECK(s.dropped() == 0);
}

TEST_CASE("axis splitter: 10 MB with no line end hold at most the bound", "[axis]") {
  AxisLineSplitter s(1 << 12);
  const std::string junk(1 << 16, 'x');
  for (int i = 0; i < 160; ++i) CHECK(split(s, {junk}).empty());
  CHECK(s.dropped() == 1);
  CHECK(split(s, {"\n0 A 1 ||\n"}) == std::vector<std::string>{"0 A 1 ||"});
  CHECK(s.line_number() == 2);
}

TEST_CASE("axis stream: garbage lines among frames are refused one by one, the frames kept", "[axis]") {
  const std::string stream =
      "0 A 1 2 3 ||\n"
      "0 A 1 2 ||\n"                    // a value short
      "hello\n"                         // not a frame
      "\x01\x02\xff\xfe ||\n"           // binary
      "0 A 1 2 3\n"                     // no ||
      "0 A 1 2 nan ||\n"                // not finite
      "0 A 4 5 6 ||\n";
  AxisLineSplitter s;
  AxisFrame f;
  std::string reason;
  std::vector<double> frames;
  int refused = 0;
  std::string_view rest = stream, line;
  while (s.next(&rest, &line)) {
    if (parse_axis_line(line, 3, &f, &reason) == AxisLineStatus::kOk) frames.push_back(f.values[0]);
    else ++refused;
  }
  CHECK(frames == std::vector<double>{1, 4});
  CHECK(refused == 5);
}
