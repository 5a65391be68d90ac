#pragma once
// The editor's command line: `mostyle [A.bvh B.bvh ... | SESSION.mostyle] [--screenshot OUT.png] [--offscreen]
// [--window-size WxH] [--paused] [--alpha A] [--components K] [--sparsity F] [--frame N]
// [--live HOST:PORT --live-skeleton FILE] [--help]`, and the list of the editor's keys (the
// shortcuts window and --help show it).
#include <optional>
#include <string>
#include <vector>

#include "engine/base/memory_limit.h"
#include "ui/model/editor_state.h"

namespace mostyle::app {

// Where the editor starts, so a screenshot is reproducible. Panels take it from EditorState.
struct InitialState {
  ui::DecompositionControls parameters;  // --components, --sparsity
  // --weights, one per take, summing to 1, or a pair's (1 - alpha, alpha) from --alpha; empty:
  // the defaults (equal weights).
  std::vector<double> weights;
  std::optional<double> alpha;  // --alpha as given (a palette has none: left unused)
  int frame = 0;  // first frame shown, of the reference (first) take
  bool paused = false;  // start with playback paused (screenshots always are)
};

constexpr int kMinWindowSide = 320;    // --window-size bounds, pixels
constexpr int kMaxWindowSide = 16384;

struct EditorOptions {
  std::vector<std::string> files;   // empty: the bundled example pair (or the session's takes)
  std::string session_path;         // a session to open (the one argument, ending in .mostyle)
  // Where the recent takes and sessions are kept across restarts (ui/model/recent_files.h); empty: not
  // kept. Not a flag: the window program sets it, tests and screenshots leave it empty.
  std::string recent_path;
  std::string screenshot_path;      // non-empty: render a few frames, write this PNG, exit
  // Non-empty: once the takes are in and the first frames drawn, the session is saved here
  // (--save-session), so that a state set up by flags can be reopened (scripted use).
  std::string save_session_path;
  bool offscreen = false;           // no display: OSMesa (needs screenshot_path)
  // --live HOST:PORT and --live-skeleton FILE (both or neither): the live source connects once
  // the takes are in (ui/model/live_source.h).
  std::string live_address, live_skeleton;
  InitialState initial;
  int width = 1280;                 // window / offscreen size, pixels (--window-size), also the
  int height = 720;                 // screenshot's; each in [kMinWindowSide, kMaxWindowSide]
  // The most memory one take's frames may need (engine/io/bvh/bvh_read.h): MOSTYLE_MAX_MEMORY_MB from
  // the environment, as mostyle-cli takes it; not a flag.
  size_t max_memory_bytes = kDefaultMaxBytes;
};

enum class ParseStatus { kRun, kHelp, kUsageError };

struct ParseResult {
  ParseStatus status = ParseStatus::kRun;
  EditorOptions options;
  std::string error;  // kUsageError: one line, e.g. "--alpha: expected a number in [0, 1], got 'x'"
};

// Parses argv (argv[0] is the program). Accepts "--flag value" and "--flag=value".
ParseResult parse_editor_options(int argc, const char* const* argv);

// Why the session given on the command line cannot be opened (unreadable or malformed, one
// line "FILE:LINE: ..."), or "" when it can (or none is given). A take of it that is missing is
// not a reason: the session opens without it. Reads the file.
std::string session_argument_error(const EditorOptions& options);

// The --help text.
std::string editor_usage();

// One line of the keys list: what to press and what it does, in plain words.
struct ShortcutHelp {
  const char* shortcut;  // "Space", "Ctrl+0", "Left drag"
  const char* action;  // "play or pause"
};

// Every key and mouse gesture the editor has, in the order the shortcuts window (F1) lists them.
const std::vector<ShortcutHelp>& editor_shortcuts();

// The bundled example pair (assets/motions/cmu142_walk_happy.bvh and ..._marching.bvh), found
// from $MOSTYLE_ASSETS, the source tree the program was built from, or beside the program.
std::vector<std::string> default_motion_files();

}  // namespace mostyle::app
