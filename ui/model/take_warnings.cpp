#include "ui/model/take_warnings.h"

#include <filesystem>
#include <utility>

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

std::vector<TakeMessages> warnings_by_take(const std::vector<std::string>& paths, const std::vector<std::string>& load,
                                           const std::vector<std::vector<std::string>>& aligned,
                                           const std::vector<std::string>& names) {
  std::vector<TakeMessages> out(paths.size());
  if (out.empty()) return out;
  for (const std::string& w : load) {
    const int take = named_file(w, paths);
    out[static_cast<size_t>(take < 0 ? 0 : take)].load.push_back(w);
  }
  // Each sentence once: where it is first given, with how many takes it was given for.
  std::vector<std::pair<std::string, int>> said;  // sentence, times given
  std::vector<std::pair<size_t, size_t>> placed;  // (take, index in its alignment list) per sentence
  for (size_t i = 0; i < aligned.size() && i < out.size(); ++i)
    for (const std::string& w : aligned[i]) {
      size_t k = 0;
      while (k < said.size() && said[k].first != w) ++k;
      if (k < said.size()) {
        ++said[k].second;
        continue;
      }
      size_t take = i;
      for (size_t j = 0; j < names.size() && j < out.size(); ++j)
        if (starts_with(w, "only " + names[j] + "'s ")) take = j;
      said.emplace_back(w, 1);
      placed.emplace_back(take, out[take].alignment.size());
      out[take].alignment.push_back(w);
    }
  for (size_t k = 0; k < said.size(); ++k)
    if (said[k].second > 1)
      out[placed[k].first].alignment[placed[k].second] += " (the same for " + std::to_string(said[k].second) + " takes)";
  return out;
}

}  // namespace mostyle::ui
