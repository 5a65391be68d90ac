#pragma once
// Numeric CSV series for the generic DTW: rows are time steps, columns features.
#include <Eigen/Core>
#include <string>
#include <string_view>

namespace mostyle {

// Parses comma-separated numbers (spaces, tabs and LF/CRLF/CR line endings allowed; blank lines
// and a UTF-8 byte order mark skipped; a first line with no number in it is taken as a header and
// fixes the column count). Throws InputError "SOURCE:LINE: expected N values, found M",
// "...: expected a finite number in column C, found 'x'" (also for a first line that mixes
// numbers and text) or "...: expected rows of numbers, found none". O(size).
Eigen::MatrixXd parse_csv_matrix(std::string_view text, const std::string& source);
Eigen::MatrixXd read_csv_matrix(const std::string& path);

}  // namespace mostyle
