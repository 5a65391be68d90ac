#pragma once
// Numeric CSV series for the generic DTW: rows are time steps, columns features.
#include <Eigen/Core>
#include <string>
#include <string_view>

#include "engine/base/memory_limit.h"

namespace mostyle {

// Parses comma-separated numbers (spaces, tabs and LF/CRLF/CR line endings allowed; blank lines
// and a UTF-8 byte order mark skipped; a first line with no number in it is taken as a header and
// fixes the column count). Throws InputError "SOURCE:LINE: expected N values, found M",
// "...: expected a finite number in column C, found 'x'" (also for a first line that mixes
// numbers and text) or "...: expected rows of numbers, found none", and "SOURCE:LINE: expected
// values within the memory limit of X, found ..." at the first row whose values (8 bytes each,
// rows so far included) would take more than max_bytes, before storing it. O(size) time; memory:
// the values twice (while parsing, and the matrix).
Eigen::MatrixXd parse_csv_matrix(std::string_view text, const std::string& source,
                                 size_t max_bytes = kDefaultMaxBytes);
// Reads the file (refused before reading when it is larger than max_bytes) and parses it.
Eigen::MatrixXd read_csv_matrix(const std::string& path, size_t max_bytes = kDefaultMaxBytes);

}  // namespace mostyle
