#include "engine/io/csv_io.h"

#include <catch2/catch.hpp>
#include <string>

#include "engine/io/error.h"

using namespace mostyle;

namespace {
std::string error_of(const std::string& text) {
  try {
    parse_csv_matrix(text, "s.csv");
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}
}  // namespace

TEST_CASE("CSV series: numbers, headers, line endings", "[csv_io]") {
  Eigen::MatrixXd expected(2, 3);
  expected << 1, -2.5, 3e2, 4, 5, 6;
  CHECK(parse_csv_matrix("1,-2.5,3e2\n4,5,6\n", "s.csv") == expected);
  CHECK(parse_csv_matrix("x,y,z\r\n1, -2.5 ,\t3e2\r\n\r\n4,+5,6", "s.csv") == expected);  // header, CRLF, blanks
  CHECK(parse_csv_matrix("1,-2.5,3e2\r4,5,6\r", "s.csv") == expected);                   // CR only
  CHECK(parse_csv_matrix("\xEF\xBB\xBF" "1,-2.5,3e2\n4,5,6\n", "s.csv") == expected);    // byte order mark
  CHECK(parse_csv_matrix("7", "s.csv") == Eigen::MatrixXd::Constant(1, 1, 7));
}

TEST_CASE("CSV series: every defect is an error with file and line", "[csv_io]") {
  CHECK(error_of("1,2\n3\n") == "s.csv:2: expected 2 values, found 1");
  CHECK(error_of("a,b\n1,2,3\n") == "s.csv:2: expected 2 values, found 3");
  CHECK(error_of("1,2\n3,x\n") == "s.csv:2: expected a finite number in column 2, found 'x'");
  CHECK(error_of("1,2\nnan,2\n") == "s.csv:2: expected a finite number in column 1, found 'nan'");
  CHECK(error_of("1,2\n1e999,2\n") == "s.csv:2: expected a finite number in column 1, found '1e999'");
  CHECK(error_of("1,2,\n") == "s.csv:1: expected a finite number in column 3, found ''");
  // A first row with one bad value is not a header that silently drops the row.
  CHECK(error_of("1,two,3\n4,5,6\n") == "s.csv:1: expected a finite number in column 2, found 'two'");
  CHECK(error_of("x,y\nfoo,bar\n") == "s.csv:2: expected a finite number in column 1, found 'foo'");
  CHECK(error_of("") == "s.csv:1: expected rows of numbers, found none");
  CHECK(error_of("x,y\n\n") == "s.csv:2: expected rows of numbers, found none");
  CHECK_THROWS_WITH(read_csv_matrix("/nonexistent/s.csv"), Catch::StartsWith("/nonexistent/s.csv"));
}
