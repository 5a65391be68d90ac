#include "ui/model/recent_files.h"

#include <algorithm>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <system_error>

#include <nlohmann/json.hpp>

#include "engine/base/atomic_file.h"
#include "engine/base/error.h"

namespace mostyle::ui {
namespace {

constexpr std::size_t kMaxRecentBytes = std::size_t{1} << 20;  // a larger file is not ours

std::vector<std::string> strings_of(const nlohmann::json& j, const char* key, std::size_t most) {
  std::vector<std::string> out;
  const auto it = j.find(key);
  if (it == j.end() || !it->is_array()) return out;
  for (const auto& item : *it) {
    if (out.size() >= most) break;
    if (!item.is_string()) continue;
    const std::string path = item.get<std::string>();
    if (!path.empty() && std::find(out.begin(), out.end(), path) == out.end()) out.push_back(path);
  }
  return out;
}

}  // namespace

void remember(std::vector<std::string>& list, const std::string& path, std::size_t most) {
  if (path.empty()) return;
  list.erase(std::remove(list.begin(), list.end(), path), list.end());
  list.insert(list.begin(), path);
  if (list.size() > most) list.resize(most);
}

std::string recent_files_path() {
  namespace fs = std::filesystem;
  if (const char* xdg = std::getenv("XDG_CONFIG_HOME"); xdg && *xdg) return (fs::path(xdg) / "mostyle" / "recent.json").string();
  if (const char* home = std::getenv("HOME"); home && *home)
    return (fs::path(home) / ".config" / "mostyle" / "recent.json").string();
  return std::string();
}

std::string format_recent_files(const RecentFiles& recent) {
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  j["takes"] = recent.takes;
  j["sessions"] = recent.sessions;
  return j.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n";
}

RecentFiles parse_recent_files(std::string_view text) {
  RecentFiles recent;
  nlohmann::json j = nlohmann::json::parse(text.begin(), text.end(), nullptr, /*allow_exceptions=*/false);
  if (!j.is_object()) return recent;  // broken (discarded) or not ours
  recent.takes = strings_of(j, "takes", kRecentTakes);
  recent.sessions = strings_of(j, "sessions", kRecentSessions);
  return recent;
}

RecentFiles read_recent_files(const std::string& path) {
  if (path.empty()) return RecentFiles();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return RecentFiles();
  try {
    return parse_recent_files(read_file(path, kMaxRecentBytes));
  } catch (const std::exception&) {  // unreadable, too large, a number too large for JSON: ignored
    return RecentFiles();
  }
}

void write_recent_files(const std::string& path, const RecentFiles& recent) {
  std::error_code ec;
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  if (!folder.empty()) std::filesystem::create_directories(folder, ec);
  if (ec) throw InputError(path + ": cannot write: " + ec.message());
  write_file_atomically(path, format_recent_files(recent));
}

}  // namespace mostyle::ui
