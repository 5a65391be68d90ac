#include "ui/model/session_file.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <initializer_list>
#include <iterator>
#include <optional>
#include <system_error>

#include <nlohmann/json.hpp>

#include "engine/align/alignment.h"
#include "engine/base/atomic_file.h"
#include "engine/base/error.h"
#include "ui/model/document_fields.h"

namespace mostyle::ui {
namespace fs = std::filesystem;
namespace {

using Json = nlohmann::json;
using OrderedJson = nlohmann::ordered_json;

// Ranges a value outside the document must be in (the document's own come with its fields,
// ui/model/document_fields.h: the ranges the controls allow).
constexpr int kMaxBand = 1000000;        // DTW band, frames
constexpr double kMaxFrames = 1e6;       // warp smoothing, frames
constexpr double kMaxPenalty = 1e300;    // DTW end penalty, feature units (negative: automatic)
constexpr double kMaxCoordinate = 1e9;   // camera target and distance, world units
constexpr double kMaxAngle = 1e6;        // camera yaw and pitch, radians (orbiting adds up)
constexpr double kMaxFov = 3.1;          // radians
constexpr double kMaxTime = 1e9;         // playhead and keys, seconds
constexpr double kMinSpeed = 0.01, kMaxSpeed = 100.0;
constexpr std::size_t kMaxQuoted = 40;   // bytes of a key or value repeated in a message
constexpr double kMaxFloat = 1e30;       // above it a double is not cast to float (undefined)
// The body regions a file names (controls.component_regions), by body_region_name.
constexpr BodyRegion kRegions[] = {BodyRegion::kSpineAndHead, BodyRegion::kLeftArm, BodyRegion::kRightArm,
                                   BodyRegion::kLeftLeg, BodyRegion::kRightLeg};

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

  double number(const Json& j, const Where& where, const Range& range) const {
    const std::string text = number_range(range.lo, range.hi, range.open_low);
    if (!j.is_number() || !in_range(j.get<double>(), range)) expected(where, text, j);
    return j.get<double>();
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

  std::vector<double> numbers(const Json& j, const Where& where, const Range& range) const {
    if (!j.is_array()) expected(where, "an array of numbers", j);
    std::vector<double> out;
    out.reserve(j.size());
    for (std::size_t i = 0; i < j.size(); ++i) out.push_back(number(j[i], where.item(i), range));
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
  j["time_base"] = time_base_name(a.time_base);
  j["on"] = align_on_name(a.on);
  j["band"] = a.band;
  j["max_slope"] = a.slope.max_slope;
  j["open_ends"] = a.slope.open_ends;
  j["end_penalty"] = a.slope.end_penalty;
  j["smoothing_frames"] = a.smoothing_frames;
  return j;
}

AlignmentOptions read_align(const Reader& r, const Json& j, const Where& w) {
  r.object(j, w);
  r.only_keys(j, w, {"method", "time_base", "on", "band", "max_slope", "open_ends", "end_penalty", "smoothing_frames"});
  AlignmentOptions a;
  // A named choice, read by the engine's parser (its sentence names the choices).
  auto choice = [&](const char* key, auto parse, auto& field) {
    r.member(j, w, key, [&](const Json& v, const Where& at) {
      const std::string name = r.string(v, at);
      try {
        field = parse(name);
      } catch (const InputError& e) {
        r.fail(at, at.name + ": " + e.what());
      }
    });
  };
  choice("method", parse_dtw_method, a.method);
  choice("time_base", parse_time_base, a.time_base);
  choice("on", parse_align_on, a.on);
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

// ---- The document: its fields from the one list (ui/model/document_fields.h) ----

// A field's place in the file: "controls.align.on" is /controls/align/on.
Where field_where(const Field& field) {
  Where w;
  w.name = field.key;
  w.pointer = "/" + w.name;
  std::replace(w.pointer.begin(), w.pointer.end(), '.', '/');
  return w;
}

std::vector<std::string> key_parts(const std::string& key) {
  std::vector<std::string> parts;
  std::size_t from = 0;
  for (std::size_t dot; (dot = key.find('.', from)) != std::string::npos; from = dot + 1)
    parts.push_back(key.substr(from, dot - from));
  parts.push_back(key.substr(from));
  return parts;
}

// A field's value as JSON: numbers, flags and lists as they are; the rest by name.
template <typename T>
OrderedJson field_json(const T& v, const fs::path&) {
  return v;
}
OrderedJson field_json(DecompositionMode mode, const fs::path&) { return decomposition_mode_name(mode); }
OrderedJson field_json(const AlignmentOptions& a, const fs::path&) { return align_json(a); }
OrderedJson field_json(const WeightKeys& keys, const fs::path&) {
  OrderedJson j = OrderedJson::array();
  for (const WeightKey& key : keys) {
    OrderedJson k = OrderedJson::object();
    k["seconds"] = key.seconds;
    k["weights"] = key.weights;
    j.push_back(k);
  }
  return j;
}
OrderedJson field_json(const std::vector<TakeLayer>& layers, const fs::path&) {
  OrderedJson j = OrderedJson::array();
  for (const TakeLayer& layer : layers) {
    OrderedJson l = OrderedJson::object();
    l["weight"] = layer.weight;
    if (!layer.component_weights.empty()) {
      OrderedJson per = OrderedJson::array();
      for (const std::optional<double>& w : layer.component_weights) per.push_back(w ? OrderedJson(*w) : OrderedJson());
      l["component_weights"] = per;
    }
    j.push_back(l);
  }
  return j;
}
OrderedJson field_json(const std::vector<BodyRegion>& regions, const fs::path&) {
  OrderedJson j = OrderedJson::array();
  for (BodyRegion r : regions) j.push_back(body_region_name(r));
  return j;
}
OrderedJson field_json(const std::vector<std::string>& takes, const fs::path& folder) {
  OrderedJson j = OrderedJson::array();
  for (const std::string& f : takes) j.push_back(take_for_file(f, folder));
  return j;
}

// A field's value read from JSON, with the field's range.
void read_field(const Reader& r, const Json& j, const Where& w, const Field& f, double& v, const fs::path&) {
  v = r.number(j, w, f.range);
}
void read_field(const Reader& r, const Json& j, const Where& w, const Field& f, int& v, const fs::path&) {
  v = r.whole(j, w, static_cast<long long>(f.range.lo), static_cast<long long>(f.range.hi));
}
void read_field(const Reader& r, const Json& j, const Where& w, const Field&, bool& v, const fs::path&) {
  v = r.boolean(j, w);
}
void read_field(const Reader& r, const Json& j, const Where& w, const Field& f, std::vector<double>& v, const fs::path&) {
  v = r.numbers(j, w, f.range);
}
// Layers: [{"weight": w, "component_weights": [w or null, ...]}, ...], each weight in the field's
// range ("weight" needed; null: the layer's weight for that component).
void read_field(const Reader& r, const Json& j, const Where& w, const Field& f, std::vector<TakeLayer>& layers,
                const fs::path&) {
  if (!j.is_array()) r.expected(w, "an array of layers {\"weight\": w, \"component_weights\": [...]}", j);
  layers.clear();
  for (std::size_t i = 0; i < j.size(); ++i) {
    const Where at = w.item(i);
    r.object(j[i], at);
    r.only_keys(j[i], at, {"weight", "component_weights"});
    if (!j[i].contains("weight")) r.fail(at, at.name + ": a layer needs \"weight\"");
    TakeLayer layer;
    layer.weight = r.number(j[i].at("weight"), at.key("weight"), f.range);
    r.member(j[i], at, "component_weights", [&](const Json& v, const Where& per) {
      if (!v.is_array()) r.expected(per, "an array of numbers or nulls", v);
      for (std::size_t c = 0; c < v.size(); ++c)
        layer.component_weights.push_back(v[c].is_null() ? std::nullopt
                                                         : std::optional<double>(r.number(v[c], per.item(c), f.range)));
    });
    layers.push_back(std::move(layer));
  }
}
// Body regions by name ("left leg", ...), as body_region_name says them.
void read_field(const Reader& r, const Json& j, const Where& w, const Field&, std::vector<BodyRegion>& regions,
                const fs::path&) {
  if (!j.is_array()) r.expected(w, "an array of body regions", j);
  regions.clear();
  for (std::size_t i = 0; i < j.size(); ++i) {
    const std::string name = r.string(j[i], w.item(i));
    const auto* found = std::find_if(std::begin(kRegions), std::end(kRegions),
                                     [&](BodyRegion region) { return name == body_region_name(region); });
    if (found == std::end(kRegions)) r.expected(w.item(i), "a body region (\"left leg\", \"spine and head\", ...)", j[i]);
    regions.push_back(*found);
  }
}
// Keys: [{"seconds": s, "weights": [...]}, ...], each weight in the field's range, then the
// engine's own check (in order of time, as many weights in each) with the line of the first key
// it refuses.
void read_field(const Reader& r, const Json& j, const Where& w, const Field& f, WeightKeys& keys, const fs::path&) {
  if (!j.is_array()) r.expected(w, "an array of keys {\"seconds\": s, \"weights\": [...]}", j);
  keys.clear();
  for (std::size_t i = 0; i < j.size(); ++i) {
    const Where at = w.item(i);
    r.object(j[i], at);
    r.only_keys(j[i], at, {"seconds", "weights"});
    for (const char* needed : {"seconds", "weights"})
      if (!j[i].contains(needed)) r.fail(at, at.name + ": a key needs \"seconds\" and \"weights\"");
    WeightKey key;
    key.seconds = r.number(j[i].at("seconds"), at.key("seconds"), 0.0, kMaxTime);
    key.weights = r.numbers(j[i].at("weights"), at.key("weights"), f.range);
    keys.push_back(std::move(key));
  }
  if (keys.empty()) return;
  const int takes = static_cast<int>(keys.front().weights.size());
  try {
    validate_keys(keys, takes);
  } catch (const InputError& e) {
    // The line of the key refused: the last of the shortest first keys refused (O(keys^2), on
    // this path only). All of them are, so the search ends at the last key at most.
    auto refused = [&](std::size_t count) {
      try {
        validate_keys(WeightKeys(keys.begin(), keys.begin() + static_cast<std::ptrdiff_t>(count)), takes);
      } catch (const InputError&) {
        return true;
      }
      return false;
    };
    std::size_t bad = 0;
    while (!refused(bad + 1)) ++bad;
    r.fail(w.item(bad), w.name + ": " + e.what());
  }
}
void read_field(const Reader& r, const Json& j, const Where& w, const Field&, DecompositionMode& v, const fs::path&) {
  const std::string mode = r.string(j, w);
  if (mode == decomposition_mode_name(DecompositionMode::kShared))
    v = DecompositionMode::kShared;
  else if (mode == decomposition_mode_name(DecompositionMode::kPaper))
    v = DecompositionMode::kPaper;
  else
    r.expected(w, "\"shared\" or \"paper\"", j);
}
void read_field(const Reader& r, const Json& j, const Where& w, const Field&, AlignmentOptions& v, const fs::path&) {
  v = read_align(r, j, w);
}
void read_field(const Reader& r, const Json& j, const Where& w, const Field& f, std::vector<std::string>& takes,
                const fs::path& folder) {
  if (!j.is_array()) r.expected(w, "an array of file names", j);
  if (static_cast<double>(j.size()) > f.range.hi)
    r.fail(w, w.name + ": more than " + number_text(f.range.hi) + " takes");
  takes.clear();
  for (std::size_t i = 0; i < j.size(); ++i) {
    const std::string name = r.string(j[i], w.item(i));
    if (name.empty()) r.fail(w.item(i), w.item(i).name + ": an empty file name");
    takes.push_back(take_from_file(name, folder));
  }
}

// Refuses a key of the object `j` at `prefix` ("" for the file, "controls." for its controls)
// that no saved field's key continues with, nor `extra`; checks that each object the keys pass
// through is one, at every level.
void check_keys(const Reader& r, const Json& j, const Where& where, const std::string& prefix,
                const std::vector<std::string>& extra) {
  std::vector<std::string> known = extra, branches;
  Document d;
  document_fields(d, d, [&](const Field& field, const auto&, const auto&) {
    const std::string key = field.key;
    if (!field.saved || key.compare(0, prefix.size(), prefix) != 0) return;
    const std::string rest = key.substr(prefix.size());
    const std::string part = rest.substr(0, rest.find('.'));
    if (std::find(known.begin(), known.end(), part) == known.end()) known.push_back(part);
    if (part != rest && std::find(branches.begin(), branches.end(), part) == branches.end()) branches.push_back(part);
  });
  for (auto it = j.begin(); it != j.end(); ++it) {
    if (std::find(known.begin(), known.end(), it.key()) != known.end()) continue;
    std::string names;
    for (const std::string& k : known) names += (names.empty() ? "" : ", ") + k;
    r.fail(where.key(it.key()), "unknown key " + quoted(it.key()) + (where.name.empty() ? "" : " in " + where.name) +
                                    " (known: " + names + ")");
  }
  for (const std::string& branch : branches) {
    const auto it = j.find(branch);
    if (it == j.end()) continue;
    r.object(*it, where.key(branch));
    check_keys(r, *it, where.key(branch), prefix + branch + ".", {});
  }
}

void write_document(OrderedJson& root, const Document& d, const fs::path& folder) {
  document_fields(d, d, [&](const Field& field, const auto& value, const auto&) {
    if (!field.saved) return;
    OrderedJson* at = &root;
    for (const std::string& part : key_parts(field.key)) at = &(*at)[part];
    *at = field_json(value, folder);
  });
}

// The document's fields from the file (keys checked already); a field left out keeps its default.
Document read_document(const Reader& r, const Json& root, const fs::path& folder) {
  Document d;
  document_fields(d, d, [&](const Field& field, auto& value, auto&) {
    if (!field.saved) return;
    const Json* at = &root;
    for (const std::string& part : key_parts(field.key)) {
      const auto it = at->find(part);
      if (it == at->end()) return;
      at = &*it;
    }
    read_field(r, *at, field_where(field), field, value, folder);
  });
  return d;
}

// Version 1 kept a pair's weights as its alpha ("parameters.alpha": the weights (1 - alpha,
// alpha)) and a palette's as "controls.palette.weights". Both are read (with the ranges version 1
// read them with) and taken out of `j`, and the weights of its takes put in as version 2 keeps
// them ("weights"): the palette's for three or more takes, else the pair's alpha; neither when
// the one its takes use is left out (the defaults: equal weights).
void read_version_1_weights(const Reader& r, Json& j) {
  const Where top;
  if (j.contains("weights"))
    r.fail(top.key("weights"), "unknown key " + quoted("weights") + " in a version 1 session (version 2 keeps the weights there)");
  std::vector<double> pair, palette;
  const auto parameters = j.find("parameters");
  if (parameters != j.end() && parameters->is_object() && parameters->contains("alpha")) {
    const double alpha = r.number(parameters->at("alpha"), top.key("parameters").key("alpha"), kAlphaRange);
    pair = {1.0 - alpha, alpha};
    parameters->erase("alpha");
  }
  const auto controls = j.find("controls");
  if (controls != j.end() && controls->is_object()) {
    const auto c = controls->find("palette");
    if (c != controls->end() && c->is_object() && c->contains("weights")) {
      palette = r.numbers(c->at("weights"), top.key("controls").key("palette").key("weights"), kMixWeightRange);
      c->erase("weights");
    }
  }
  const auto takes = j.find("takes");
  const std::size_t n = takes != j.end() && takes->is_array() ? takes->size() : 0;
  const std::vector<double>& weights = n >= 3 ? palette : pair;
  if (!weights.empty()) j["weights"] = weights;
}

// Version 2 kept the weights apart from their layers: "weights" (one per take), a pair's
// "controls.per_component" and "controls.component_alpha" (per component, B's weight), and
// "controls.palette": {"per_part", "part_weights" ([legs, arms, spine] x takes, an empty row: the
// weights), "transfer", "content", "neutral", "content_neutral", "strengths", "ghosts"}. They are
// read (with the ranges version 2 read them with), taken out of `j`, and put in as version 3 keeps
// them: "layers" (a palette's transfer its strengths, anything else its weights; a pair's
// component alphas as (1 - alpha_c, alpha_c), a palette's part rows as weights per body region),
// "controls.per_part", "controls.component_regions" and the transfer's and ghosts' own keys (a
// pair's takes always stood beside its result: ghosts on).
void read_version_2_layers(const Reader& r, Json& j) {
  const Where top, controls_at = top.key("controls"), palette_at = controls_at.key("palette");
  const auto takes = j.find("takes");
  const std::size_t n = takes != j.end() && takes->is_array() ? takes->size() : 0;
  std::vector<double> weights, component_alpha, strengths;
  std::vector<std::vector<double>> part_rows;
  bool per_component = false, per_part = false, transfer = false, content_neutral = false, ghosts = false;
  int neutral = 1;
  if (j.contains("weights")) weights = r.numbers(j["weights"], top.key("weights"), kMixWeightRange);
  j.erase("weights");
  if (!j.contains("controls")) j["controls"] = Json::object();
  Json& controls = j["controls"];
  r.object(controls, controls_at);
  r.member(controls, controls_at, "per_component", [&](const Json& v, const Where& at) { per_component = r.boolean(v, at); });
  r.member(controls, controls_at, "component_alpha",
           [&](const Json& v, const Where& at) { component_alpha = r.numbers(v, at, kAlphaRange); });
  if (controls.contains("palette")) {
    const Json& p = r.object(controls["palette"], palette_at);
    r.only_keys(p, palette_at, {"per_part", "part_weights", "transfer", "content", "neutral", "content_neutral",
                                "strengths", "ghosts"});
    r.member(p, palette_at, "per_part", [&](const Json& v, const Where& at) { per_part = r.boolean(v, at); });
    r.member(p, palette_at, "part_weights", [&](const Json& v, const Where& at) {
      if (!v.is_array()) r.expected(at, "an array of arrays of numbers", v);
      for (std::size_t i = 0; i < v.size(); ++i) part_rows.push_back(r.numbers(v[i], at.item(i), kMixWeightRange));
    });
    r.member(p, palette_at, "transfer", [&](const Json& v, const Where& at) { transfer = r.boolean(v, at); });
    r.member(p, palette_at, "content", [&](const Json& v, const Where& at) { r.whole(v, at, 0, kMaxPaletteTakes - 1); });
    r.member(p, palette_at, "neutral", [&](const Json& v, const Where& at) { neutral = r.whole(v, at, 0, kMaxPaletteTakes - 1); });
    r.member(p, palette_at, "content_neutral", [&](const Json& v, const Where& at) { content_neutral = r.boolean(v, at); });
    r.member(p, palette_at, "strengths", [&](const Json& v, const Where& at) { strengths = r.numbers(v, at, kStrengthRange); });
    r.member(p, palette_at, "ghosts", [&](const Json& v, const Where& at) { ghosts = r.boolean(v, at); });
  }
  for (const char* key : {"per_component", "component_alpha", "palette"}) controls.erase(key);
  const bool palette = n >= 3;
  // The layers' weights: a palette's transfer mixed its strengths (1 where none was set).
  std::vector<double> layer_weights = weights;
  if (palette && transfer) {
    strengths.resize(n, 1.0);
    layer_weights = strengths;
  }
  std::vector<OrderedJson> per(n, OrderedJson());
  auto set_per = [&](std::size_t take, std::size_t at, double w) {
    if (per[take].is_null()) per[take] = OrderedJson::array();
    while (per[take].size() <= at) per[take].push_back(nullptr);
    per[take][at] = w;
  };
  if (!palette && n == 2 && !component_alpha.empty()) {  // kept by index (no regions known)
    for (std::size_t c = 0; c < component_alpha.size(); ++c) {
      set_per(0, c, 1.0 - component_alpha[c]);
      set_per(1, c, component_alpha[c]);
    }
  }
  constexpr BodyPart kRowParts[] = {BodyPart::kLegs, BodyPart::kArms, BodyPart::kSpine};
  bool by_region = false;
  for (std::size_t row = 0; palette && row < part_rows.size() && row < std::size(kRowParts); ++row) {
    if (part_rows[row].size() != n) continue;  // the part followed the weights
    for (std::size_t g = 0; g < std::size(kRegions); ++g)
      if (part_covers(kRowParts[row], kRegions[g]))
        for (std::size_t i = 0; i < n; ++i) set_per(i, g, part_rows[row][i]);
    by_region = true;
  }
  if (layer_weights.size() == n || std::any_of(per.begin(), per.end(), [](const OrderedJson& p) { return !p.is_null(); })) {
    OrderedJson layers = OrderedJson::array();
    for (std::size_t i = 0; i < n; ++i) {
      OrderedJson l = OrderedJson::object();
      l["weight"] = layer_weights.size() == n ? layer_weights[i] : 1.0 / static_cast<double>(n);
      if (!per[i].is_null()) l["component_weights"] = per[i];
      layers.push_back(l);
    }
    j["layers"] = layers;
  }
  if (by_region) {
    OrderedJson regions = OrderedJson::array();
    for (BodyRegion g : kRegions) regions.push_back(body_region_name(g));
    controls["component_regions"] = regions;
  }
  controls["per_part"] = palette ? per_part : per_component;
  controls["transfer"] = transfer;
  controls["neutral"] = neutral;
  controls["content_neutral"] = content_neutral;
  controls["ghosts"] = palette ? ghosts : true;
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
  write_document(j, d, folder);
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
  if (*version < 1 || *version > kSessionVersion)
    r.fail(top.key("version"), "version " + a_json_type(*version) +
                                   " is not one this mostyle reads (it reads versions 1 to " +
                                   std::to_string(kSessionVersion) + ")");
  if (*version == 1) read_version_1_weights(r, j);
  if (*version <= 2) read_version_2_layers(r, j);
  check_keys(r, j, top, "", {"version", "camera", "playback"});

  SessionFile session;
  session.document = read_document(r, j, session_folder(session_path));
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

std::string missing_takes_message(const std::string& session_path, const std::vector<std::string>& missing,
                                  bool others_open) {
  if (missing.empty()) return std::string();
  std::string names;
  for (std::size_t i = 0; i < missing.size(); ++i)
    names += (i == 0 ? "" : i + 1 == missing.size() ? " and " : ", ") + missing[i];
  return one_line(session_path + ": cannot find the take" + (missing.size() > 1 ? "s " : " ") + names +
                  (others_open ? "; the other takes and the rest of the session are open"
                               : "; the rest of the session is restored, and the takes loaded before stay") +
                  ", and the session file is left as it is (put the take back and open it again, or save as a new "
                  "file with Ctrl+Shift+S to keep the session without it)");
}

bool is_session_path(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  return ext == kSessionExtension;
}

}  // namespace mostyle::ui
