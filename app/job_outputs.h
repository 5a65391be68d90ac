#pragma once
// The files a job (one JOBS line's arguments) writes, for `mostyle-cli batch --skip-existing`.
#include <string>
#include <vector>

namespace mostyle::cli {

// The values of the output options in a command's arguments: --out, --positions-out, --report
// and --jobs-out, as "--out FILE" or "--out=FILE", in order. A command that names its output
// otherwise (convert's positional OUT) or writes none (info, dtw) gives none. Arguments after a
// lone "--" are another command's options (grid's blend options) and are not looked at. Pure;
// O(arguments).
std::vector<std::string> job_outputs(const std::vector<std::string>& args);

}  // namespace mostyle::cli
