#include "engine/io/csv/csv_read.h"

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <string>

#include "engine/base/error.h"

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

TEST_CASE("CSV series: values over the memory limit are refused at their line, before they are stored",
          "[csv_io]") {
  // 100 rows of 4 values: 3200 bytes. A limit of 1000 bytes holds 125 values: 31 rows.
  std::string text = "a,b,c,d\n";
  for (int r = 0; r < 100; ++r) text += "1,2,3,4\n";
  CHECK(parse_csv_matrix(text, "m.csv", 3200).rows() == 100);
  try {
    parse_csv_matrix(text, "m.csv", 1000);
    FAIL("no error");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()) ==
          "m.csv:33: expected values within the memory limit of 1000 bytes, found 32 rows of 4 values each (1 KB)");
  }
  // A file larger than the limit is not read at all.
  const std::string path = (std::filesystem::temp_directory_path() / "mostyle_csv_limit_test.csv").string();
  std::ofstream(path, std::ios::binary) << text;
  CHECK_THROWS_WITH(read_csv_matrix(path, 500), path + ": cannot read: its 808 bytes exceed the memory limit of 500 bytes");
  CHECK_THROWS_WITH(read_csv_matrix(path, 1000), Catch::StartsWith(path + ":33: expected values within the memory"));
  CHECK(read_csv_matrix(path).rows() == 100);
  std::filesystem::remove(path);
}
