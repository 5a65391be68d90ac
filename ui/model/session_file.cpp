#include "ui/model/session_file.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <initializer_list>
#include <system_error>

#include <nlohmann/json.hpp>

#include "engine/align/alignment.h"
#include "engine/io/atomic_file.h"
#include "engine/io/error.h"
#include "engine/run/palette.h"

namespace mostyle::ui {
namespace fs = std::filesystem;
namespace {

using Json = nlohmann::json;
using OrderedJson = nlohmann::ordered_json;

// Ranges a value must be in. The palette's weights and strengths are read with the ranges their
// sliders allow (engine/run/palette.h), so every session the editor writes reopens; elsewhere
// wide where the panels are narrow: a session written by hand may go further than the sliders.
constexpr int kMaxComponents = 1000;
constexpr int kMaxBasicMotions = 16;
constexpr std::size_t kMaxTakes = 64;
constexpr int kMaxBand = 1000000;        // DTW band, frames
constexpr double kMaxFrames = 1e6;       // warp smoothing, frames
constexpr double kMaxPenalty = 1e300;    // DTW end penalty, feature units (negative: automatic)
constexpr double kMaxCoordinate = 1e9;   // camera target and distance, world units
constexpr double kMaxAngle = 1e6;        // camera yaw and pitch, radians (orbiting adds up)
constexpr double kMaxFov = 3.1;          // radians
constexpr double kMaxTime = 1e9;         // playhead, seconds
constexpr double kMinSpeed = 0.01, kMaxSpeed = 100.0;
constexpr std::size_t kMaxQuoted = 40;   // bytes of a key or value repeated in a message
constexpr double kMaxFloat = 1e30;       // above it a double is not cast to float (undefined)

// ---- Where a value is in the text, for the line of a message ----

// Calls visit(offset, pointer) for each value of a JSON text in order, with its JSON pointer
// ("/controls/align/on", "/takes/1", "" for the whole text), until visit returns true. Not a
// validator: any bytes go through in O(size x depth) time, so it also serves text the parser
// refused past the value looked for.
template <typename Visit>
void scan_values(std::string_view text, Visit visit) {
  struct Level {
    bool object;
    long index;
    std::size_t base;  // path.size() of the container itself
  };
  std::vector<Level> levels;
  std::string path;
  bool want_key = false;
  const std::size_t n = text.size();
  auto end_of_string = [&](std::size_t i) {  // i at the opening quote: just past the closing one
    for (++i; i < n; ++i) {
      if (text[i] == '\\')
        ++i;
      else if (text[i] == '"')
        return i + 1;
    }
    return n;
  };
  auto element_path = [&](const Level& level) {
    path.resize(level.base);
    path += '/';
    path += std::to_string(level.index);
  };
  std::size_t i = 0;
  while (i < n) {
    const char c = text[i];
    if (c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == ':') {
      ++i;
    } else if (c == ',') {
      if (!levels.empty()) {
        Level& level = levels.back();
        if (level.object) {
          want_key = true;
        } else {
          ++level.index;
          element_path(level);
        }
      }
      ++i;
    } else if (c == '}' || c == ']') {
      if (!levels.empty()) {
        path.resize(levels.back().base);
        levels.pop_back();
      }
      want_key = false;
      ++i;
    } else if (c == '"' && want_key && !levels.empty() && levels.back().object) {
      const std::size_t end = end_of_string(i);
      const std::size_t stop = end > i + 1 && end <= n && text[end - 1] == '"' ? end - 1 : n;
      path.resize(levels.back().base);
      path += '/';
      path.append(text.substr(i + 1, stop - (i + 1)));
      want_key = false;
      i = end;
    } else {
      if (visit(i, path)) return;
      if (c == '{') {
        levels.push_back({true, 0, path.size()});
        want_key = true;
        ++i;
      } else if (c == '[') {
        levels.push_back({false, 0, path.size()});
        element_path(levels.back());
        ++i;
      } else if (c == '"') {
        i = end_of_string(i);
      } else {
        while (i < n && std::string_view(" \t\r\n,:{}[]\"").find(text[i]) == std::string_view::npos) ++i;
      }
    }
  }
}

// Offset of the value at `pointer`; npos when there is none.
std::size_t locate(std::string_view text, const std::string& pointer) {
  std::size_t found = std::string_view::npos;
  scan_values(text, [&](std::size_t at, const std::string& path) {
    if (path != pointer) return false;
    found = at;
    return true;
  });
  return found;
}

// Offset of the first number too large for a double (nlohmann refuses it without a position).
std::size_t first_overflow(std::string_view text) {
  std::size_t found = std::string_view::npos;
  scan_values(text, [&](std::size_t at, const std::string&) {
    if (text[at] != '-' && !std::isdigit(static_cast<unsigned char>(text[at]))) return false;
    std::size_t end = at;
    while (end < text.size() && std::string_view(" \t\r\n,:{}[]\"").find(text[end]) == std::string_view::npos) ++end;
    const std::string token(text.substr(at, end - at));
    if (std::isfinite(std::strtod(token.c_str(), nullptr))) return false;
    found = at;
    return true;
  });
  return found;
}

int line_at(std::string_view text, std::size_t offset) {
  if (offset == std::string_view::npos) return 1;
  offset = std::min(offset, text.size());
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(offset), '\n'));
}

// A key or string from the file as a message repeats it: quoted, control bytes as '?', cut short.
std::string quoted(const std::string& s) {
  std::string out = "'";
  for (std::size_t i = 0; i < s.size() && i < kMaxQuoted; ++i)
    out += static_cast<unsigned char>(s[i]) < 0x20 || s[i] == 0x7f ? '?' : s[i];
  return out + (s.size() > kMaxQuoted ? "...'" : "'");
}

std::string one_line(std::string s) {
  std::replace(s.begin(), s.end(), '\n', ' ');
  std::replace(s.begin(), s.end(), '\r', ' ');
  return s;
}

std::string number_text(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", v);
  return buffer;
}

// "a number from 0 to 1", "a number above 0, up to 1".
std::string number_range(double lo, double hi, bool open_low) {
  return open_low ? "a number above " + number_text(lo) + ", up to " + number_text(hi)
                  : "a number from " + number_text(lo) + " to " + number_text(hi);
}

std::string a_json_type(const Json& j) {
  if (j.is_null()) return "null";
  if (j.is_boolean()) return j.get<bool>() ? "true" : "false";
  if (j.is_number()) return one_line(j.dump());
  if (j.is_string()) return "the string " + quoted(j.get<std::string>());
  const std::string name = j.type_name();
  return (name[0] == 'a' || name[0] == 'o' ? "an " : "a ") + name;
}

// ---- Reading ----

// A value's place: its JSON pointer (for the line) and its name as messages say it.
struct Where {
  std::string pointer;  // "/controls/align/on"
  std::string name;     // "controls.align.on", "takes[1]"
  Where key(const std::string& k) const { return {pointer + "/" + k, name.empty() ? k : name + "." + k}; }
  Where item(std::size_t i) const { return {pointer + "/" + std::to_string(i), name + "[" + std::to_string(i) + "]"}; }
};

class Reader {
 public:
  Reader(std::string_view text, const std::string& source) : text_(text), source_(source) {}

  [[noreturn]] void fail(const Where& where, const std::string& what) const {
    std::string pointer = where.pointer;
    std::size_t at = locate(text_, pointer);
    while (at == std::string_view::npos && !pointer.empty()) {  // a missing key: its object's line
      pointer.resize(pointer.rfind('/'));
      at = locate(text_, pointer);
    }
    throw InputError(one_line(source_ + ":" + std::to_string(line_at(text_, at)) + ": " + what));
  }
  [[noreturn]] void expected(const Where& where, const std::string& what, const Json& found) const {
    fail(where, where.name + ": expected " + what + ", found " + a_json_type(found));
  }

  // Fails on a key of `j` (an object) that is not in `known`.
  void only_keys(const Json& j, const Where& where, std::initializer_list<const char*> known) const {
    for (auto it = j.begin(); it != j.end(); ++it) {
      if (std::any_of(known.begin(), known.end(), [&](const char* k) { return it.key() == k; })) continue;
      std::string names;
      for (const char* k : known) names += std::string(names.empty() ? "" : ", ") + k;
      fail(where.key(it.key()), "unknown key " + quoted(it.key()) + (where.name.empty() ? "" : " in " + where.name) +
                                    " (known: " + names + ")");
    }
  }

  // Calls read(value, where) for member `key` of object `j` when it is there.
  template <typename Read>
  void member(const Json& j, const Where& where, const char* key, Read read) const {
    const auto it = j.find(key);
    if (it != j.end()) read(*it, where.key(key));
  }

  const Json& object(const Json& j, const Where& where) const {
    if (!j.is_object()) expected(where, "an object { ... }", j);
    return j;
  }

  double number(const Json& j, const Where& where, double lo, double hi, bool open_low = false) const {
    const std::string range = number_range(lo, hi, open_low);
    if (!j.is_number()) expected(where, range, j);
    const double v = j.get<double>();
    if (!std::isfinite(v) || v < lo || (open_low && v <= lo) || v > hi) expected(where, range, j);
    return v;
  }

  // Checked as the float it becomes, so that what is written reads back (0.01 is 0.0099999998f).
  float number_float(const Json& j, const Where& where, double lo, double hi, bool open_low = false) const {
    const std::string range = number_range(lo, hi, open_low);
    if (!j.is_number()) expected(where, range, j);
    const double v = j.get<double>();
    if (!std::isfinite(v) || std::fabs(v) > kMaxFloat) expected(where, range, j);  // before the cast
    const float f = static_cast<float>(v), low = static_cast<float>(lo), high = static_cast<float>(hi);
    if (f < low || (open_low && f <= low) || f > high) expected(where, range, j);
    return f;
  }

  int whole(const Json& j, const Where& where, long long lo, long long hi) const {
    const std::string range = "a whole number from " + std::to_string(lo) + " to " + std::to_string(hi);
    if (!j.is_number_integer()) expected(where, range, j);
    if (j.is_number_unsigned()) {
      const std::uint64_t v = j.get<std::uint64_t>();
      if (hi < 0 || v > static_cast<std::uint64_t>(hi) || static_cast<long long>(v) < lo) expected(where, range, j);
      return static_cast<int>(v);
    }
    const std::int64_t v = j.get<std::int64_t>();
    if (v < lo || v > hi) expected(where, range, j);
    return static_cast<int>(v);
  }

  bool boolean(const Json& j, const Where& where) const {
    if (!j.is_boolean()) expected(where, "true or false", j);
    return j.get<bool>();
  }

  std::string string(const Json& j, const Where& where) const {
    if (!j.is_string()) expected(where, "a string", j);
    return j.get<std::string>();
  }

  std::vector<double> numbers(const Json& j, const Where& where, double lo, double hi, bool open_low = false) const {
    if (!j.is_array()) expected(where, "an array of numbers", j);
    std::vector<double> out;
    out.reserve(j.size());
    for (std::size_t i = 0; i < j.size(); ++i) out.push_back(number(j[i], where.item(i), lo, hi, open_low));
    return out;
  }

 private:
  std::string_view text_;
  std::string source_;
};

// ---- Paths of takes ----

fs::path session_folder(const std::string& session_path) {
  return fs::path(session_path).parent_path().lexically_normal();
}

// As written: relative to the session's folder when that reads back as the same path.
std::string take_for_file(const std::string& take, const fs::path& folder) {
  const fs::path p = fs::path(take).lexically_normal();
  const fs::path relative = p.lexically_relative(folder);
  if (!relative.empty() && (folder / relative).lexically_normal() == p) return relative.generic_string();
  return p.generic_string();
}

// As loaded: resolved against the session's folder.
std::string take_from_file(const std::string& stored, const fs::path& folder) {
  const fs::path p(stored);
  return (p.is_absolute() ? p : folder / p).lexically_normal().string();
}

// ---- The sections ----

// A float as the shortest decimal that reads back (double, then cast) as the same float: 0.65,
// not 0.6499999761581421.
double float_for_json(float f) {
  for (int digits = 6; digits <= 9; ++digits) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, static_cast<double>(f));
    const double d = std::strtod(buffer, nullptr);
    if (static_cast<float>(d) == f) return d;
  }
  return static_cast<double>(f);
}

OrderedJson align_json(const AlignmentOptions& a) {
  OrderedJson j = OrderedJson::object();
  j["method"] = dtw_method_name(a.method);
  j["on"] = align_on_name(a.on);
  j["band"] = a.band;
  j["max_slope"] = a.slope.max_slope;
  j["open_ends"] = a.slope.open_ends;
  j["end_penalty"] = a.slope.end_penalty;
  j["smoothing_frames"] = a.smoothing_frames;
  return j;
}

OrderedJson palette_json(const PaletteControls& p) {
  OrderedJson j = OrderedJson::object();
  j["weights"] = p.weights;
  j["per_part"] = p.per_part;
  j["part_weights"] = p.part_weights;
  j["transfer"] = p.transfer;
  j["content"] = p.content;
  j["neutral"] = p.neutral;
  j["strengths"] = p.strengths;
  j["ghosts"] = p.ghosts;
  return j;
}

OrderedJson controls_json(const SessionControls& c) {
  OrderedJson j = OrderedJson::object();
  j["mode"] = blend_mode_name(c.mode);
  j["per_component"] = c.per_component;
  j["component_alpha"] = c.component_alpha;
  j["basic_motions"] = c.basic_motions;
  j["basic_sparsities"] = c.basic_sparsities;
  j["swap_level"] = c.swap_level;
  j["foot_lock"] = c.foot_lock;
  j["timing_a"] = c.timing_a;
  j["loop"] = c.loop;
  j["residual"] = c.residual;
  j["align"] = align_json(c.align);
  j["palette"] = palette_json(c.palette);
  return j;
}

AlignmentOptions read_align(const Reader& r, const Json& j, const Where& w) {
  r.object(j, w);
  r.only_keys(j, w, {"method", "on", "band", "max_slope", "open_ends", "end_penalty", "smoothing_frames"});
  AlignmentOptions a;
  r.member(j, w, "method", [&](const Json& v, const Where& at) {
    const std::string name = r.string(v, at);
    try {
      a.method = parse_dtw_method(name);
    } catch (const InputError& e) {  // the engine's sentence names the choices
      r.fail(at, at.name + ": " + e.what());
    }
  });
  r.member(j, w, "on", [&](const Json& v, const Where& at) {
    const std::string name = r.string(v, at);
    try {
      a.on = parse_align_on(name);
    } catch (const InputError& e) {
      r.fail(at, at.name + ": " + e.what());
    }
  });
  r.member(j, w, "band", [&](const Json& v, const Where& at) { a.band = r.whole(v, at, -1, kMaxBand); });
  r.member(j, w, "max_slope", [&](const Json& v, const Where& at) { a.slope.max_slope = r.whole(v, at, 2, 4); });
  r.member(j, w, "open_ends", [&](const Json& v, const Where& at) { a.slope.open_ends = r.boolean(v, at); });
  r.member(j, w, "end_penalty",
           [&](const Json& v, const Where& at) { a.slope.end_penalty = r.number(v, at, -kMaxPenalty, kMaxPenalty); });
  r.member(j, w, "smoothing_frames",
           [&](const Json& v, const Where& at) { a.smoothing_frames = r.number(v, at, 0.0, kMaxFrames); });
  try {
    a.Validate();  // the ranges above should hold it; the engine has the last word
  } catch (const InputError& e) {
    r.fail(w, w.name + ": " + e.what());
  }
  return a;
}

PaletteControls read_palette(const Reader& r, const Json& j, const Where& w) {
  r.object(j, w);
  r.only_keys(j, w, {"weights", "per_part", "part_weights", "transfer", "content", "neutral", "strengths", "ghosts"});
  PaletteControls p;
  const int last_take = static_cast<int>(kMaxTakes) - 1;
  r.member(j, w, "weights", [&](const Json& v, const Where& at) { p.weights = r.numbers(v, at, kMinMixWeight, kMaxMixWeight); });
  r.member(j, w, "per_part", [&](const Json& v, const Where& at) { p.per_part = r.boolean(v, at); });
  r.member(j, w, "part_weights", [&](const Json& v, const Where& at) {
    if (!v.is_array()) r.expected(at, "an array of arrays of numbers", v);
    for (std::size_t i = 0; i < v.size(); ++i) p.part_weights.push_back(r.numbers(v[i], at.item(i), kMinMixWeight, kMaxMixWeight));
  });
  r.member(j, w, "transfer", [&](const Json& v, const Where& at) { p.transfer = r.boolean(v, at); });
  r.member(j, w, "content", [&](const Json& v, const Where& at) { p.content = r.whole(v, at, 0, last_take); });
  r.member(j, w, "neutral", [&](const Json& v, const Where& at) { p.neutral = r.whole(v, at, 0, last_take); });
  r.member(j, w, "strengths",
           [&](const Json& v, const Where& at) { p.strengths = r.numbers(v, at, kMinStrength, kMaxStrength); });
  r.member(j, w, "ghosts", [&](const Json& v, const Where& at) { p.ghosts = r.boolean(v, at); });
  return p;
}

SessionControls read_controls(const Reader& r, const Json& j, const Where& w) {
  r.object(j, w);
  r.only_keys(j, w, {"mode", "per_component", "component_alpha", "basic_motions", "basic_sparsities", "swap_level",
                     "foot_lock", "timing_a", "loop", "residual", "align", "palette"});
  SessionControls c;
  r.member(j, w, "mode", [&](const Json& v, const Where& at) {
    const std::string mode = r.string(v, at);
    if (mode == blend_mode_name(BlendMode::kShared))
      c.mode = BlendMode::kShared;
    else if (mode == blend_mode_name(BlendMode::kPaper))
      c.mode = BlendMode::kPaper;
    else
      r.expected(at, "\"shared\" or \"paper\"", v);
  });
  r.member(j, w, "per_component", [&](const Json& v, const Where& at) { c.per_component = r.boolean(v, at); });
  r.member(j, w, "component_alpha",
           [&](const Json& v, const Where& at) { c.component_alpha = r.numbers(v, at, 0.0, 1.0); });
  r.member(j, w, "basic_motions",
           [&](const Json& v, const Where& at) { c.basic_motions = r.whole(v, at, 0, kMaxBasicMotions); });
  r.member(j, w, "basic_sparsities",
           [&](const Json& v, const Where& at) { c.basic_sparsities = r.numbers(v, at, 0.0, 1.0, /*open_low=*/true); });
  r.member(j, w, "swap_level", [&](const Json& v, const Where& at) {
    c.swap_level = r.whole(v, at, 0, std::max(c.basic_motions - 1, 0));  // a level of basic_motions
  });
  r.member(j, w, "foot_lock", [&](const Json& v, const Where& at) { c.foot_lock = r.boolean(v, at); });
  r.member(j, w, "timing_a", [&](const Json& v, const Where& at) { c.timing_a = r.boolean(v, at); });
  r.member(j, w, "loop", [&](const Json& v, const Where& at) { c.loop = r.boolean(v, at); });
  r.member(j, w, "residual", [&](const Json& v, const Where& at) { c.residual = r.boolean(v, at); });
  r.member(j, w, "align", [&](const Json& v, const Where& at) { c.align = read_align(r, v, at); });
  r.member(j, w, "palette", [&](const Json& v, const Where& at) { c.palette = read_palette(r, v, at); });
  return c;
}

BlendParameters read_parameters(const Reader& r, const Json& j, const Where& w) {
  r.object(j, w);
  r.only_keys(j, w, {"alpha", "components", "sparsity"});
  BlendParameters p;
  r.member(j, w, "alpha", [&](const Json& v, const Where& at) { p.alpha = r.number(v, at, 0.0, 1.0); });
  r.member(j, w, "components", [&](const Json& v, const Where& at) { p.components = r.whole(v, at, 1, kMaxComponents); });
  r.member(j, w, "sparsity",
           [&](const Json& v, const Where& at) { p.sparsity = r.number(v, at, 0.0, 1.0, /*open_low=*/true); });
  return p;
}

SessionCamera read_camera(const Reader& r, const Json& j, const Where& w) {
  r.object(j, w);
  r.only_keys(j, w, {"target", "yaw", "pitch", "distance", "fov_y"});
  SessionCamera c;
  r.member(j, w, "target", [&](const Json& v, const Where& at) {
    if (!v.is_array() || v.size() != 3) r.expected(at, "an array of 3 numbers [x, y, z]", v);
    for (std::size_t i = 0; i < 3; ++i) c.target[i] = r.number_float(v[i], at.item(i), -kMaxCoordinate, kMaxCoordinate);
  });
  r.member(j, w, "yaw", [&](const Json& v, const Where& at) { c.yaw = r.number_float(v, at, -kMaxAngle, kMaxAngle); });
  r.member(j, w, "pitch", [&](const Json& v, const Where& at) { c.pitch = r.number_float(v, at, -kMaxAngle, kMaxAngle); });
  r.member(j, w, "distance",
           [&](const Json& v, const Where& at) { c.distance = r.number_float(v, at, 0.0, kMaxCoordinate, /*open_low=*/true); });
  r.member(j, w, "fov_y",
           [&](const Json& v, const Where& at) { c.fov_y = r.number_float(v, at, 0.0, kMaxFov, /*open_low=*/true); });
  return c;
}

Playback read_playback(const Reader& r, const Json& j, const Where& w) {
  r.object(j, w);
  r.only_keys(j, w, {"time_s", "playing", "speed", "loop"});
  Playback p;
  r.member(j, w, "time_s", [&](const Json& v, const Where& at) { p.time_s = r.number(v, at, 0.0, kMaxTime); });
  r.member(j, w, "playing", [&](const Json& v, const Where& at) { p.playing = r.boolean(v, at); });
  r.member(j, w, "speed", [&](const Json& v, const Where& at) { p.speed = r.number_float(v, at, kMinSpeed, kMaxSpeed); });
  r.member(j, w, "loop", [&](const Json& v, const Where& at) { p.loop = r.boolean(v, at); });
  return p;
}

// The parser's reason without its own "[json.exception...] parse error at line L, column C: ".
std::string parser_reason(const std::string& what) {
  const std::size_t column = what.find("column ");
  const std::size_t colon = what.find(": ", column == std::string::npos ? 0 : column);
  return colon == std::string::npos ? what : what.substr(colon + 2);
}

}  // namespace

bool operator==(const SessionCamera& x, const SessionCamera& y) {
  return x.target == y.target && x.yaw == y.yaw && x.pitch == y.pitch && x.distance == y.distance &&
         x.fov_y == y.fov_y;
}

std::string format_session(const SessionFile& session, const std::string& session_path) {
  const fs::path folder = session_folder(session_path);
  const Document& d = session.document;
  OrderedJson j = OrderedJson::object();
  j["version"] = kSessionVersion;
  OrderedJson takes = OrderedJson::array();
  for (const std::string& f : d.files) takes.push_back(take_for_file(f, folder));
  j["takes"] = takes;
  OrderedJson parameters = OrderedJson::object();
  parameters["alpha"] = d.parameters.alpha;
  parameters["components"] = d.parameters.components;
  parameters["sparsity"] = d.parameters.sparsity;
  j["parameters"] = parameters;
  j["controls"] = controls_json(d.controls);
  OrderedJson view = OrderedJson::object();
  view["overlay"] = d.overlay;
  j["view"] = view;
  if (session.camera) {
    const SessionCamera& c = *session.camera;
    OrderedJson camera = OrderedJson::object();
    camera["target"] = {float_for_json(c.target[0]), float_for_json(c.target[1]), float_for_json(c.target[2])};
    camera["yaw"] = float_for_json(c.yaw);
    camera["pitch"] = float_for_json(c.pitch);
    camera["distance"] = float_for_json(c.distance);
    camera["fov_y"] = float_for_json(c.fov_y);
    j["camera"] = camera;
  }
  OrderedJson playback = OrderedJson::object();
  playback["time_s"] = session.playback.time_s;
  playback["playing"] = session.playback.playing;
  playback["speed"] = float_for_json(session.playback.speed);
  playback["loop"] = session.playback.loop;
  j["playback"] = playback;
  // Paths are bytes: a take whose name is not UTF-8 is written with U+FFFD, not refused.
  return j.dump(2, ' ', false, OrderedJson::error_handler_t::replace) + "\n";
}

SessionFile parse_session(std::string_view text, const std::string& session_path) {
  const Reader r(text, session_path);
  const Where top;
  Json j;
  try {
    j = Json::parse(text.begin(), text.end());
  } catch (const Json::parse_error& e) {
    const std::size_t at = e.byte > 0 ? e.byte - 1 : 0;  // e.byte counts from 1
    throw InputError(one_line(session_path + ":" + std::to_string(line_at(text, at)) +
                              ": not a mostyle session (not valid JSON: " + parser_reason(e.what()) + ")"));
  } catch (const Json::out_of_range&) {  // "1e400": a number too large for a double, no position given
    throw InputError(session_path + ":" + std::to_string(line_at(text, first_overflow(text))) +
                     ": a number too large for a double");
  }
  if (!j.is_object())
    r.fail(top, "expected a mostyle session (a JSON object with \"version\": " + std::to_string(kSessionVersion) +
                    "), found " + a_json_type(j));
  // The version first: a later version's new keys are not typos.
  const auto version = j.find("version");
  if (version == j.end())
    r.fail(top, "no \"version\": not a mostyle session (expected \"version\": " + std::to_string(kSessionVersion) + ")");
  if (!version->is_number_integer()) r.expected(top.key("version"), "a whole number", *version);
  if (*version != kSessionVersion)
    r.fail(top.key("version"), "version " + a_json_type(*version) + " is not one this mostyle reads (it reads version " +
                                   std::to_string(kSessionVersion) + ")");
  r.only_keys(j, top, {"version", "takes", "parameters", "controls", "view", "camera", "playback"});

  SessionFile session;
  Document& d = session.document;
  const fs::path folder = session_folder(session_path);
  r.member(j, top, "takes", [&](const Json& v, const Where& at) {
    if (!v.is_array()) r.expected(at, "an array of file names", v);
    if (v.size() > kMaxTakes) r.fail(at, at.name + ": more than " + std::to_string(kMaxTakes) + " takes");
    for (std::size_t i = 0; i < v.size(); ++i) {
      const std::string name = r.string(v[i], at.item(i));
      if (name.empty()) r.fail(at.item(i), at.item(i).name + ": an empty file name");
      d.files.push_back(take_from_file(name, folder));
    }
  });
  r.member(j, top, "parameters", [&](const Json& v, const Where& at) { d.parameters = read_parameters(r, v, at); });
  r.member(j, top, "controls", [&](const Json& v, const Where& at) { d.controls = read_controls(r, v, at); });
  r.member(j, top, "view", [&](const Json& v, const Where& at) {
    r.object(v, at);
    r.only_keys(v, at, {"overlay"});
    r.member(v, at, "overlay", [&](const Json& o, const Where& o_at) { d.overlay = r.boolean(o, o_at); });
  });
  r.member(j, top, "camera", [&](const Json& v, const Where& at) { session.camera = read_camera(r, v, at); });
  r.member(j, top, "playback", [&](const Json& v, const Where& at) { session.playback = read_playback(r, v, at); });
  return session;
}

SessionFile read_session_file(const std::string& path) { return parse_session(read_file(path, kMaxSessionBytes), path); }

void write_session_file(const std::string& path, const SessionFile& session) {
  write_file_atomically(path, format_session(session, path));
}

std::vector<std::string> missing_takes(const Document& document) {
  std::vector<std::string> missing;
  for (const std::string& f : document.files) {
    std::error_code ec;
    if (fs::exists(f, ec) || std::find(missing.begin(), missing.end(), f) != missing.end()) continue;
    missing.push_back(f);
  }
  return missing;
}

std::string missing_takes_message(const std::string& session_path, const std::vector<std::string>& missing) {
  if (missing.empty()) return std::string();
  std::string names;
  for (std::size_t i = 0; i < missing.size(); ++i)
    names += (i == 0 ? "" : i + 1 == missing.size() ? " and " : ", ") + missing[i];
  return one_line(session_path + ": cannot find the take" + (missing.size() > 1 ? "s " : " ") + names +
                  "; the rest of the session is restored, and the takes loaded before stay");
}

bool is_session_path(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  return ext == kSessionExtension;
}

}  // namespace mostyle::ui
