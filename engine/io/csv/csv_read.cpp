#include "engine/io/csv/csv_read.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <string>
#include <vector>

#include "engine/base/atomic_file.h"
#include "engine/base/error.h"

namespace mostyle {
namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

bool parse_number(std::string_view token, double* v) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty()) return false;
  auto r = std::from_chars(token.data(), token.data() + token.size(), *v);
  return r.ec == std::errc() && r.ptr == token.data() + token.size();
}

}  // namespace

Eigen::MatrixXd parse_csv_matrix(std::string_view text, const std::string& source, size_t max_bytes) {
  std::vector<double> values;
  long long columns = -1, rows = 0;
  int line_number = 0;
  size_t pos = 0;
  if (text.substr(0, 3) == "\xEF\xBB\xBF") pos = 3;  // a UTF-8 byte order mark (spreadsheet exports)
  while (pos < text.size()) {
    size_t end = text.find_first_of("\r\n", pos);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = trim(text.substr(pos, end - pos));
    pos = end + ((end + 1 < text.size() && text[end] == '\r' && text[end + 1] == '\n') ? 2 : 1);
    ++line_number;
    if (line.empty()) continue;
    std::vector<std::string_view> tokens;
    size_t start = 0;
    for (;;) {
      const size_t comma = line.find(',', start);
      tokens.push_back(trim(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start)));
      if (comma == std::string_view::npos) break;
      start = comma + 1;
    }
    std::vector<double> row(tokens.size());
    bool numeric = true, any_number = false;
    size_t bad = 0;
    for (size_t i = 0; i < tokens.size(); ++i) {
      double ignored = 0;
      const bool number = parse_number(tokens[i], &row[i]) && std::isfinite(row[i]);
      // "nan" and "inf" parse but are not numbers a header would hold.
      any_number = any_number || number || parse_number(tokens[i], &ignored);
      if (!number && numeric) {
        numeric = false;
        bad = i;
      }
    }
    const std::string where = source + ":" + std::to_string(line_number) + ": ";
    if (!numeric) {
      // A header: the first line, made of names only. A first row with one bad number is an
      // error like any other, not a header that silently drops the row.
      if (rows == 0 && columns < 0 && !any_number) {
        columns = static_cast<long long>(tokens.size());
        continue;
      }
      throw InputError(where + "expected a finite number in column " + std::to_string(bad + 1) +
                       ", found '" + std::string(tokens[bad].substr(0, 40)) + "'");
    }
    if (columns < 0) columns = static_cast<long long>(tokens.size());
    if (static_cast<long long>(tokens.size()) != columns)
      throw InputError(where + "expected " + std::to_string(columns) + " values, found " +
                       std::to_string(tokens.size()));
    if (row.size() > max_bytes / sizeof(double) - values.size())
      throw InputError(where + "expected values within the memory limit of " + describe_bytes(max_bytes) + ", found " +
                       std::to_string(rows + 1) + " rows of " + std::to_string(row.size()) +
                       (row.size() == 1 ? " value each (" : " values each (") +
                       describe_bytes((values.size() + row.size()) * sizeof(double)) + ")");
    values.insert(values.end(), row.begin(), row.end());
    ++rows;
  }
  if (rows == 0) throw InputError(source + ":" + std::to_string(std::max(line_number, 1)) + ": expected rows of numbers, found none");
  Eigen::MatrixXd m(rows, columns);
  for (long long r = 0; r < rows; ++r)
    for (long long c = 0; c < columns; ++c) m(r, c) = values[r * columns + c];
  return m;
}

Eigen::MatrixXd read_csv_matrix(const std::string& path, size_t max_bytes) {
  return parse_csv_matrix(read_file(path, max_bytes), path, max_bytes);
}

}  // namespace mostyle
