#pragma once
// The editor's command line: `mostyle [A.bvh B.bvh ...] [--screenshot OUT.png] [--offscreen]
// [--alpha A] [--components K] [--sparsity F] [--frame N] [--help]`.
#include <string>
#include <vector>

#include "ui/editor_state.h"

namespace mostyle::app {

// Where the editor starts, so a screenshot is reproducible. Panels take it from EditorState.
struct InitialState {
  ui::BlendParameters parameters;
  int frame = 0;  // first frame shown, of the reference (first) take
};

struct EditorOptions {
  std::vector<std::string> files;   // empty: the bundled example pair
  std::string screenshot_path;      // non-empty: render a few frames, write this PNG, exit
  bool offscreen = false;           // no display: OSMesa (needs screenshot_path)
  InitialState initial;
  int width = 1280;                 // window / offscreen size, pixels
  int height = 720;
};

enum class ParseStatus { kRun, kHelp, kUsageError };

struct ParseResult {
  ParseStatus status = ParseStatus::kRun;
  EditorOptions options;
  std::string error;  // kUsageError: one line, e.g. "--alpha: expected a number in [0, 1], got 'x'"
};

// Parses argv (argv[0] is the program). Accepts "--flag value" and "--flag=value".
ParseResult parse_editor_options(int argc, const char* const* argv);

// The --help text.
std::string editor_usage();

// The bundled example pair (assets/motions/cmu142_walk_happy.bvh and ..._marching.bvh), found
// from $MOSTYLE_ASSETS, the source tree the program was built from, or beside the program.
std::vector<std::string> default_motion_files();

}  // namespace mostyle::app
