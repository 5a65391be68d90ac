// mostyle, the editor, in a window (libGL). --offscreen runs hand over to mostyle-offscreen,
// the same editor linked to OSMesa: one process cannot safely have both libraries provide
// the GL entry points (whichever is linked first takes every call), see app/CMakeLists.txt.
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include "app/editor/editor_options.h"
#include "app/editor/window_platform.h"
#include "ui/model/recent_files.h"

namespace {

int exec_offscreen(int argc, char** argv) {
  std::error_code ec;
  std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  std::filesystem::path sibling = ec ? std::filesystem::path("mostyle-offscreen")
                                     : self.parent_path() / "mostyle-offscreen";
  std::string program = sibling.string();
  std::vector<char*> args(argv, argv + argc);
  args[0] = program.data();
  args.push_back(nullptr);
  execv(program.c_str(), args.data());
  std::fprintf(stderr, "mostyle: --offscreen needs %s: %s\n", program.c_str(), std::strerror(errno));
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace mostyle::app;
  ParseResult parsed = parse_editor_options(argc, argv);
  switch (parsed.status) {
    case ParseStatus::kHelp:
      std::fputs(editor_usage().c_str(), stdout);
      return 0;
    case ParseStatus::kUsageError:
      std::fprintf(stderr, "mostyle: %s\n", parsed.error.c_str());
      return 2;
    case ParseStatus::kRun:
      break;
  }
  // A session that cannot be opened is said here, before any window: nothing else opens instead.
  if (const std::string error = session_argument_error(parsed.options); !error.empty()) {
    std::fprintf(stderr, "mostyle: %s\n", error.c_str());
    return 1;
  }
  if (parsed.options.offscreen) return exec_offscreen(argc, argv);
  // The recent takes and sessions outlive the window; a screenshot run leaves them alone.
  if (parsed.options.screenshot_path.empty()) parsed.options.recent_path = mostyle::ui::recent_files_path();
  return run_window(parsed.options);
}
