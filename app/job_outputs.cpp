#include "app/job_outputs.h"

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

}  // namespace mostyle::cli
