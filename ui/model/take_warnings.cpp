#include "ui/model/take_warnings.h"

#include <filesystem>

#include "engine/io/motion_file.h"

namespace mostyle::ui {
namespace {

bool starts_with(const std::string& text, const std::string& start) {
  return !start.empty() && text.compare(0, start.size(), start) == 0;
}

// The take whose file `warning` starts with, the path as given before its file name alone (two
// takes from different folders may share a name); -1: none.
int named_file(const std::string& warning, const std::vector<std::string>& paths) {
  for (bool whole : {true, false})
    for (size_t i = 0; i < paths.size(); ++i) {
      const std::string file = split_take_path(paths[i]).path;
      const std::string name = whole ? file : std::filesystem::path(file).filename().string();
      if (starts_with(warning, name + ":")) return static_cast<int>(i);
    }
  return -1;
}

}  // namespace

std::vector<std::vector<std::string>> warnings_by_take(const std::vector<std::string>& paths,
                                                       const std::vector<std::string>& load,
                                                       const std::vector<std::vector<std::string>>& aligned,
                                                       const std::vector<std::string>& names) {
  std::vector<std::vector<std::string>> out(paths.size());
  if (out.empty()) return out;
  for (const std::string& w : load) {
    const int take = named_file(w, paths);
    out[static_cast<size_t>(take < 0 ? 0 : take)].push_back(w);
  }
  for (size_t i = 0; i < aligned.size() && i < out.size(); ++i)
    for (const std::string& w : aligned[i]) {
      size_t take = i;
      for (size_t j = 0; j < names.size() && j < out.size(); ++j)
        if (starts_with(w, "only " + names[j] + "'s ")) take = j;
      out[take].push_back(w);
    }
  return out;
}

}  // namespace mostyle::ui
