#include "app/batch/job_line.h"

#include <catch2/catch.hpp>
#include <string>

#include "engine/base/error.h"

using mostyle::cli::parse_job_line;

namespace {

std::string error_of(const std::string& line) {
  try {
    parse_job_line(line, "jobs.jsonl", 4);
  } catch (const mostyle::InputError& e) {
    return e.what();
  }
  return "(no error)";
}

const std::string kExpected =
    "jobs.jsonl:4: expected a JSON array of strings (the arguments of one mostyle-cli command), found ";

}  // namespace

TEST_CASE("parse_job_line: an array of strings is one command's arguments", "[job_line]") {
  using Args = std::vector<std::string>;
  CHECK(parse_job_line(R"(["info", "a.bvh"])", "j", 1) == Args{"info", "a.bvh"});
  CHECK(parse_job_line("  [\"blend\",\"a b.bvh\",\"--out\",\"\\u00e9.bvh\"]\r", "j", 1) ==
        Args{"blend", "a b.bvh", "--out", "\xc3\xa9.bvh"});
}

TEST_CASE("parse_job_line: every other line is refused with its line number", "[job_line]") {
  CHECK(error_of(R"({"cmd": "info"})") == kExpected + "an object");
  CHECK(error_of(R"(["info", 3])") == kExpected + "a number as item 2");
  CHECK(error_of(R"(["info", null])") == kExpected + "null as item 2");
  CHECK(error_of(R"(["info", ["a"]])") == kExpected + "an array as item 2");
  CHECK(error_of("\"info\"") == kExpected + "a string");
  CHECK(error_of("[\"info\"") == kExpected + "invalid JSON at column 8");
  CHECK(error_of("[\"info\"] x") == kExpected + "invalid JSON at column 10");
  CHECK(error_of("[\"\xff\"]") == kExpected + "invalid JSON at column 3");  // not UTF-8
  // Found by tests/fuzz (regressions/job_line/): nlohmann throws out_of_range, not parse_error.
  CHECK(error_of("[1e400, \"x\"]") == kExpected + "a number too large for JSON");
  CHECK(error_of("[\"info\", -1e400]") == kExpected + "a number too large for JSON");
  CHECK(error_of("[]") == "jobs.jsonl:4: expected a mostyle-cli command such as [\"blend\", ...], found an empty array");
  CHECK(error_of(R"(["batch", "more.jsonl"])") == "jobs.jsonl:4: a job cannot be a batch itself");
  // Deep nesting is an error, not a stack overflow.
  CHECK(error_of(std::string(100000, '[') + std::string(100000, ']')) == kExpected + "an array as item 1");
}
