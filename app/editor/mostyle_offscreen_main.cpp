// mostyle-offscreen: the editor with no display (OSMesa), for `mostyle --offscreen` (which
// runs this program) and for CI screenshots. Same flags as mostyle; --offscreen is implied.
#include <cstdio>
#include <string>

#include "app/editor/editor_options.h"
#include "app/editor/offscreen_platform.h"

int main(int argc, char** argv) {
  using namespace mostyle::app;
  ParseResult parsed = parse_editor_options(argc, argv);
  if (parsed.status == ParseStatus::kHelp) {
    std::fputs(editor_usage().c_str(), stdout);
    return 0;
  }
  if (parsed.status == ParseStatus::kUsageError) {
    std::fprintf(stderr, "mostyle: %s\n", parsed.error.c_str());
    return 2;
  }
  if (parsed.options.screenshot_path.empty()) {
    std::fprintf(stderr, "mostyle: --offscreen renders for a screenshot: add --screenshot OUT.png\n");
    return 2;
  }
  // A session that cannot be opened is said here, before any window: nothing else opens instead.
  if (const std::string error = session_argument_error(parsed.options); !error.empty()) {
    std::fprintf(stderr, "mostyle: %s\n", error.c_str());
    return 1;
  }
  return run_offscreen(parsed.options);
}
