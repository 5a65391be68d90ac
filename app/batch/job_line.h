#pragma once
// One line of a JOBS file (`mostyle-cli batch`): a JSON array of strings, the arguments of one
// mostyle-cli command, e.g. ["blend", "a.bvh", "b.bvh", "--out", "ab.bvh"].
#include <string>
#include <string_view>
#include <vector>

namespace mostyle::cli {

// The arguments of one non-blank JOBS line (a trailing '\r' is allowed). Throws InputError
// "SOURCE:LINE: expected a JSON array of strings (the arguments of one mostyle-cli command),
// found ..." naming what was found (invalid JSON and its column, a number too large, another
// JSON type, a non-string item), and "SOURCE:LINE: ..." for an empty array or a nested batch.
// Pure: no I/O.
// O(line length) time and memory.
std::vector<std::string> parse_job_line(std::string_view line, const std::string& source,
                                        int line_number);

}  // namespace mostyle::cli
