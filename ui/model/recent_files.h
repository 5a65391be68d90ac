#pragma once
// The takes and sessions opened before, newest first, kept across restarts in
// $XDG_CONFIG_HOME/mostyle/recent.json (else $HOME/.config/mostyle/recent.json):
//   {"takes": ["/data/walk_happy.bvh", ...], "sessions": ["/data/day1.mostyle", ...]}
// Only what loaded goes in (a mistyped path never does). A broken or missing file reads as an
// empty list: it is a convenience, never a reason not to start.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace mostyle::ui {

constexpr std::size_t kRecentTakes = 8;
constexpr std::size_t kRecentSessions = 8;

struct RecentFiles {
  std::vector<std::string> takes;     // .bvh files that loaded, newest first, at most kRecentTakes
  std::vector<std::string> sessions;  // .mostyle files opened or saved, newest first, at most kRecentSessions
};

// Puts `path` first in `list` (taking it out further down) and keeps at most `most` entries.
void remember(std::vector<std::string>& list, const std::string& path, std::size_t most);

// Where the list is kept; "" when neither XDG_CONFIG_HOME nor HOME is set. Creates nothing.
std::string recent_files_path();

// JSON text of the list, and back. parse_recent_files never throws: what is not a list of
// strings under "takes" or "sessions" is left out (empty strings and extra entries too). Pure.
std::string format_recent_files(const RecentFiles& recent);
RecentFiles parse_recent_files(std::string_view text);

// Reads the list at `path`; empty when it is missing, unreadable or broken. Never throws.
RecentFiles read_recent_files(const std::string& path);
// Writes the list at `path` atomically, making its folder first. Throws InputError
// ("PATH: cannot write: ...").
void write_recent_files(const std::string& path, const RecentFiles& recent);

}  // namespace mostyle::ui
