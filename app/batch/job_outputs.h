#pragma once
// The files a job (one JOBS line's arguments) writes, for `mostyle-cli batch --skip-existing`,
// and what a killed job left of them.
#include <string>
#include <vector>

namespace mostyle::cli {

// The values of the output options in a command's arguments: --out, --positions-out, --report
// and --jobs-out, as "--out FILE" or "--out=FILE", in order. A command that names its output
// otherwise (convert's positional OUT) or writes none (info, dtw) gives none. Arguments after a
// lone "--" are another command's options (grid's blend options) and are not looked at. Pure;
// O(arguments).
std::vector<std::string> job_outputs(const std::vector<std::string>& args);

// Removes what a killed job left of its outputs: every output is written to a temporary file
// OUTPUT.tmp<PID>_<N> beside it (engine/base/atomic_file) and renamed, so a job killed between the
// two leaves that file. Removes only those of process `pid`; returns how many it removed. Never
// throws (a folder that cannot be listed is left alone). O(files in the outputs' folders).
int remove_leftovers(const std::vector<std::string>& outputs, int pid);

}  // namespace mostyle::cli
