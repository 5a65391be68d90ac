#include "app/batch/job_outputs.h"

#include <algorithm>
#include <filesystem>
#include <string_view>

namespace mostyle::cli {

std::vector<std::string> job_outputs(const std::vector<std::string>& args) {
  static const std::string_view kOutputOptions[] = {"--out", "--positions-out", "--report", "--jobs-out"};
  std::vector<std::string> outputs;
  for (size_t k = 0; k < args.size(); ++k) {
    const std::string_view arg = args[k];
    if (arg == "--") break;
    for (std::string_view option : kOutputOptions) {
      if (arg == option && k + 1 < args.size()) {
        outputs.push_back(args[++k]);
        break;
      }
      if (arg.size() > option.size() && arg.substr(0, option.size()) == option && arg[option.size()] == '=') {
        outputs.emplace_back(arg.substr(option.size() + 1));
        break;
      }
    }
  }
  return outputs;
}

int remove_leftovers(const std::vector<std::string>& outputs, int pid) {
  namespace fs = std::filesystem;
  int removed = 0;
  for (const std::string& output : outputs) {
    const fs::path path(output);
    const std::string prefix = path.filename().string() + ".tmp" + std::to_string(pid) + "_";
    const fs::path folder = path.has_parent_path() ? path.parent_path() : fs::path(".");
    std::error_code ec;
    for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
      const std::string name = it->path().filename().string();
      const std::string_view counter = std::string_view(name).substr(std::min(prefix.size(), name.size()));
      if (name.compare(0, prefix.size(), prefix) != 0 || counter.empty() ||
          counter.find_first_not_of("0123456789") != std::string_view::npos)
        continue;
      std::error_code removing;
      removed += fs::remove(it->path(), removing) ? 1 : 0;
    }
  }
  return removed;
}

}  // namespace mostyle::cli
