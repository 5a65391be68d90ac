#pragma once
// Numeric CSV series for the generic DTW: rows are time steps, columns features.
#include <Eigen/Core>
#include <string>
#include <string_view>

namespace mostyle {

// Parses comma-separated numbers (spaces, tabs and LF/CRLF/CR line endings allowed; blank lines
// skipped; a first line that is not numeric is taken as a header). Throws InputError
// "SOURCE:LINE: expected N values, found M" or "...: expected a finite number, found 'x'".
Eigen::MatrixXd parse_csv_matrix(std::string_view text, const std::string& source);
Eigen::MatrixXd read_csv_matrix(const std::string& path);

}  // namespace mostyle
