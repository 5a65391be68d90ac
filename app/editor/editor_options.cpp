#include "app/editor/editor_options.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <system_error>

#include "engine/base/error.h"
#include "engine/base/numbers.h"
#include "engine/synthesize/mix_palette.h"
#include "ui/model/session_file.h"

namespace mostyle::app {
namespace {

bool parse_double(const std::string& text, double* out) {
  char* end = nullptr;
  *out = std::strtod(text.c_str(), &end);
  return !text.empty() && end == text.c_str() + text.size() && std::isfinite(*out);
}

bool parse_int(const std::string& text, int* out) {
  auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), *out);
  return !text.empty() && ec == std::errc() && ptr == text.data() + text.size();
}

// "WIDTHxHEIGHT", each a whole number in [kMinWindowSide, kMaxWindowSide].
bool parse_size(const std::string& text, int* width, int* height) {
  const size_t x = text.find_first_of("xX");
  if (x == std::string::npos) return false;
  return parse_int(text.substr(0, x), width) && parse_int(text.substr(x + 1), height) && *width >= kMinWindowSide &&
         *width <= kMaxWindowSide && *height >= kMinWindowSide && *height <= kMaxWindowSide;
}

std::filesystem::path program_directory() {
  std::error_code ec;
  std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::filesystem::path() : exe.parent_path();
}

// One "--name" or "--name=value" argument; take_value() reads its value (after '=', else the
// next argument, moving *i past it).
struct Flag {
  std::string name, value;
  bool has_value = false;  // given as --name=value
  int argc = 0;
  const char* const* argv = nullptr;
  int* i = nullptr;

  bool take_value() {
    if (has_value) return true;
    if (*i + 1 >= argc) return false;
    value = argv[++*i];
    return true;
  }
};

Flag split_flag(const std::string& arg, int argc, const char* const* argv, int* i) {
  Flag f;
  f.name = arg;
  f.argc = argc;
  f.argv = argv;
  f.i = i;
  if (size_t eq = arg.find('='); eq != std::string::npos) {
    f.name = arg.substr(0, eq);
    f.value = arg.substr(eq + 1);
    f.has_value = true;
  }
  return f;
}

// --weights: one per take, comma separated, normalised; the usage error, or "".
std::string read_weights(Flag& f, InitialState& initial) {
  const std::string& value = f.value;
  std::vector<double> weights;
  bool ok = f.take_value() && !value.empty();
  for (size_t begin = 0; ok && begin <= value.size();) {
    const size_t comma = std::min(value.find(',', begin), value.size());
    double w = 0.0;
    ok = parse_number(value.substr(begin, comma - begin), &w) && w >= kMinMixWeight && w <= kMaxMixWeight;
    weights.push_back(w);
    begin = comma + 1;
  }
  weights = normalized_weights(weights);
  double sum = 0.0;
  for (double w : weights) sum += w;
  if (!ok || weights.size() < 2 || std::abs(sum - 1.0) > 1e-9)
    return "--weights: expected one weight per take, comma separated (decimals or fractions such as 1/3), "
           "each from -0.5 to 1.5, summing to 1, got '" + value + "'";
  initial.weights = weights;
  return "";
}

// Every flag but --help; the usage error, or "".
std::string read_flag(Flag& f, EditorOptions& o) {
  const std::string& name = f.name;
  const std::string& value = f.value;
  if (name == "--offscreen") {
    if (f.has_value) return "--offscreen takes no value";
    o.offscreen = true;
  } else if (name == "--paused") {
    if (f.has_value) return "--paused takes no value";
    o.initial.paused = true;
  } else if (name == "--window-size") {
    int w = 0, h = 0;
    if (!f.take_value() || !parse_size(value, &w, &h))
      return "--window-size: expected WIDTHxHEIGHT in pixels, each " + std::to_string(kMinWindowSide) + " to " +
             std::to_string(kMaxWindowSide) + " (e.g. 1920x1080), got '" + value + "'";
    o.width = w;
    o.height = h;
  } else if (name == "--screenshot") {
    if (!f.take_value() || value.empty()) return "--screenshot: expected an output file name";
    o.screenshot_path = value;
  } else if (name == "--save-session") {
    if (!f.take_value() || value.empty()) return "--save-session: expected a session file name (.mostyle)";
    if (!ui::is_session_path(value) && !std::filesystem::path(value).extension().empty())
      return "--save-session: a session's file name ends in .mostyle, got '" + value + "'";
    o.save_session_path = value;
  } else if (name == "--alpha") {
    double v = 0.0;
    // The rule `blend --alpha` has: B's weight, and A's 1 - alpha, within a mix's range.
    if (!f.take_value() || !parse_double(value, &v) || v < kMinMixWeight || v > kMaxMixWeight)
      return "--alpha: expected a number from -0.5 to 1.5, got '" + value + "'";
    o.initial.alpha = v;
  } else if (name == "--components") {
    int v = 0;
    if (!f.take_value() || !parse_int(value, &v) || v < 1)
      return "--components: expected a whole number >= 1, got '" + value + "'";
    o.initial.parameters.components = v;
  } else if (name == "--sparsity") {
    double v = 0.0;
    if (!f.take_value() || !parse_double(value, &v) || v <= 0.0 || v > 1.0)
      return "--sparsity: expected a number in (0, 1], got '" + value + "'";
    o.initial.parameters.sparsity = v;
  } else if (name == "--weights") {
    return read_weights(f, o.initial);
  } else if (name == "--live") {
    if (!f.take_value() || value.empty()) return "--live: expected HOST:PORT of a BVH broadcasting server";
    o.live_address = value;
  } else if (name == "--live-skeleton") {
    if (!f.take_value() || value.empty()) return "--live-skeleton: expected the stream's skeleton, a BVH file";
    o.live_skeleton = value;
  } else if (name == "--frame") {
    int v = 0;
    if (!f.take_value() || !parse_int(value, &v) || v < 0)
      return "--frame: expected a whole number >= 0, got '" + value + "'";
    o.initial.frame = v;
  } else {
    return "unknown option '" + name + "' (see --help)";
  }
  return "";
}

// What the flags and files mean together, and the memory limit from the environment: the
// usage error, or "". A session given moves from o.files to o.session_path.
std::string check_options(EditorOptions& o) {
  if (o.offscreen && o.screenshot_path.empty()) return "--offscreen renders for a screenshot: add --screenshot OUT.png";
  if (o.live_address.empty() != o.live_skeleton.empty())
    return "--live and --live-skeleton go together: the stream's address and its skeleton (a BVH file)";
  try {
    const char* limit = std::getenv(kMemoryLimitVariable);
    o.max_memory_bytes = parse_memory_limit(limit ? limit : "");
  } catch (const InputError& e) {
    return e.what();
  }
  // A session brings its own takes: it is the one file given.
  for (const std::string& f : o.files) {
    if (!ui::is_session_path(f)) continue;
    if (o.files.size() != 1) return "'" + f + "' is a session: it opens alone, without other files";
    o.session_path = f;
    o.files.clear();
    break;
  }
  const size_t takes = o.files.empty() ? 2 : std::max<size_t>(o.files.size(), 2);
  // --alpha: a pair's weights, unless --weights gives them (more takes and a session have no alpha).
  if (o.initial.alpha && o.initial.weights.empty() && o.session_path.empty() && takes == 2)
    o.initial.weights = {1.0 - *o.initial.alpha, *o.initial.alpha};
  if (!o.initial.weights.empty()) {
    if (!o.session_path.empty()) return "--weights: a session brings its own weights; give takes instead";
    if (o.initial.weights.size() != takes)
      return "--weights: expected " + std::to_string(takes) + " weights, one per take, got " +
             std::to_string(o.initial.weights.size());
  }
  return "";
}

}  // namespace

ParseResult parse_editor_options(int argc, const char* const* argv) {
  ParseResult result;
  EditorOptions& o = result.options;
  auto fail = [&](const std::string& message) {
    result.status = ParseStatus::kUsageError;
    result.error = message;
    return result;
  };
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    if (arg.size() < 2 || arg.compare(0, 2, "--") != 0 || arg == "--") {
      if (arg == "--") {
        for (++i; i < argc; ++i) o.files.emplace_back(argv[i]);
        break;
      }
      if (arg.size() > 1 && arg[0] == '-') {
        if (arg == "-h") {
          result.status = ParseStatus::kHelp;
          return result;
        }
        return fail("unknown option '" + arg + "' (see --help)");
      }
      o.files.push_back(arg);
      continue;
    }
    Flag flag = split_flag(arg, argc, argv, &i);
    if (flag.name == "--help") {
      result.status = ParseStatus::kHelp;
      return result;
    }
    if (const std::string error = read_flag(flag, o); !error.empty()) return fail(error);
  }
  if (const std::string error = check_options(o); !error.empty()) return fail(error);
  return result;
}

std::string session_argument_error(const EditorOptions& options) {
  if (options.session_path.empty()) return "";
  try {
    ui::read_session_file(options.session_path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

const std::vector<ShortcutHelp>& editor_shortcuts() {
  static const std::vector<ShortcutHelp> kKeys = {
      {"Space", "play or pause (from the start again on the last frame)"},
      {"Left / Right arrow", "step one frame back / forward (pauses)"},
      {"K", "key the style at the playhead: the takes' weights (the timeline's Set key)"},
      {"Delete", "remove the key under the mouse on the timeline, else the one at the playhead"},
      {"F", "frame all: turn and move the camera to show every skeleton"},
      {"F1 or ?", "show or hide this list of keys"},
      {"Esc", "close this list"},
      {"Ctrl+0", "reset the layout: every panel back in its place for this window size"},
      {"Ctrl+E", "export the blend: the export dialog (file, frame rate, frames, channels)"},
      {"Ctrl+Z", "undo: a parameter, weight, mode, option or load back as it was (a slider drag is one step)"},
      {"Ctrl+Shift+Z or Ctrl+Y", "redo what was undone"},
      {"Ctrl+S", "save the session (.mostyle: takes, parameters, camera, playback); asks where the first time"},
      {"Ctrl+Shift+S", "save the session under another name"},
      {"Ctrl+O", "open a session (.mostyle)"},
      {"Enter", "in a file field: load that file; in the export field: open the export dialog"},
      {"Left drag", "in the 3D view: turn the camera around the skeletons"},
      {"Right or middle drag", "in the 3D view: move the camera sideways and up or down"},
      {"Mouse wheel", "in the 3D view: move the camera closer or further"},
      {"Drag a key's diamond", "on the timeline: move the key in time; click: go to it; right-click: remove it"},
      {"Drop .bvh files", "on the window: two or more are the new takes, one is one more take"},
  };
  return kKeys;
}

std::string editor_usage() {
  std::string keys;
  for (const ShortcutHelp& k : editor_shortcuts()) {
    std::string line = std::string("  ") + k.shortcut;
    line.resize(std::max<size_t>(line.size() + 1, 24), ' ');
    keys += line + k.action + "\n";
  }
  return "usage: mostyle [A.bvh B.bvh ... | SESSION.mostyle] [options]\n"
         "\n"
         "Blend the styles of motion-capture takes live. With no files, opens the bundled\n"
         "example pair (CMU subject 142: happy and marching walks). Two to sixteen files are\n"
         "mixed alike, each a layer with its weight, the first the reference. A session\n"
         "(.mostyle, saved with Ctrl+S) opens its takes with every parameter, the camera and\n"
         "the playback.\n"
         "\n"
         "options:\n"
         "  --screenshot OUT.png  render the first frames, write a PNG of the whole window, exit\n"
         "  --offscreen           no display needed (OSMesa); use with --screenshot\n"
         "  --window-size WxH     window and screenshot size in pixels (default 1280x720)\n"
         "  --paused              start with playback paused\n"
         "  --alpha A             initial blend, 0 = first take, 1 = second, -0.5 to 1.5 (default 0.5)\n"
         "  --components K        initial number of components (default 10)\n"
         "  --sparsity F          initial fraction of non-zeros per component, (0, 1] (default 0.1)\n"
         "  --frame N             initial frame (default 0)\n"
         "  --weights W1,W2,...   initial weights, one per take, summing to 1 (a pair's: 1-alpha,alpha)\n"
         "  --save-session FILE   once the takes are in, save the session to FILE (.mostyle)\n"
         "  --live HOST:PORT      once the takes are in, style the BVH broadcasting stream there with\n"
         "                        them (the stream as the first take, every other take a style at its\n"
         "                        weight); with --screenshot, the picture is taken once a\n"
         "                        second of it is styled\n"
         "  --live-skeleton FILE  the stream's skeleton: a BVH file with its hierarchy and channels\n"
         "  --help                this text\n"
         "\n"
         "keys and mouse (F1 in the editor lists them too):\n" +
         keys +
         "\n"
         "exit status: 0 success, 1 failure (no display, a session that cannot be opened, an unwritable\n"
         "screenshot or session), 2 bad usage.\n";
}

std::vector<std::string> default_motion_files() {
  namespace fs = std::filesystem;
  std::vector<fs::path> roots;
  if (const char* env = std::getenv("MOSTYLE_ASSETS")) roots.emplace_back(env);
#ifdef MOSTYLE_SOURCE_ASSETS_DIR
  roots.emplace_back(MOSTYLE_SOURCE_ASSETS_DIR);
#endif
  fs::path here = program_directory();
  if (!here.empty()) {
    roots.push_back(here / "assets");
    roots.push_back(here.parent_path() / "assets");
    roots.push_back(here.parent_path() / "share" / "mostyle" / "assets");
  }
  const char* const names[] = {"cmu142_walk_happy.bvh", "cmu142_walk_marching.bvh"};
  for (const fs::path& root : roots) {
    std::error_code ec;
    if (fs::exists(root / "motions" / names[0], ec)) {
      return {(root / "motions" / names[0]).string(), (root / "motions" / names[1]).string()};
    }
  }
  // Not found: the names alone, so the load error in the UI says what is missing.
  return {std::string("assets/motions/") + names[0], std::string("assets/motions/") + names[1]};
}

}  // namespace mostyle::app
