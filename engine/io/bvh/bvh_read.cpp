#include "engine/io/bvh/bvh_read.h"

#include <algorithm>
#include <cctype>
#include <cfloat>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdint>
#include <string>

#include "engine/base/atomic_file.h"
#include "engine/base/error.h"
#include "engine/base/huge_pages.h"

namespace mostyle {
namespace {

// Limits that keep a hostile file from allocating or running away.
constexpr long long kMaxFrames = 100'000'000;  // more than a day at 1000 fps
constexpr int kMaxChannelsPerJoint = 6;
constexpr size_t kShownTokenLength = 40;
// A frame value takes at least two bytes ("0 "): the frames a text can hold, whatever it declares.
constexpr size_t kMinBytesPerValue = 2;

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\f' || c == '\v'; }
bool is_eol(char c) { return c == '\n' || c == '\r'; }
bool is_separator(char c) { return is_space(c) || is_eol(c); }

bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    if (std::tolower(static_cast<unsigned char>(a[i])) !=
        std::tolower(static_cast<unsigned char>(b[i])))
      return false;
  }
  return true;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

// A token as it may be shown in a message: quoted, printable, short.
std::string shown(std::string_view token) {
  return token.empty() ? "end of line" : quoted_bytes(token, kShownTokenLength);
}

// The frame values real files hold ("-23.251000", "0", "1.5"): an optional '-', at most 19
// digits around an optional '.', at most 22 of them after it, no exponent. When the digits make
// an integer m <= 2^53, the value is m / 10^k with both operands exact doubles, and one IEEE
// division rounds it correctly: the double std::from_chars gives, bit for bit (Clinger's fast
// path; W. D. Clinger, "How to read floating point numbers accurately", PLDI 1990, section 5).
// Returns where the number stops, or nullptr for anything else, which std::from_chars then
// reads. Nearly twice as fast as std::from_chars alone on the CMU takes (tests/bench/bvh_bench).
const char* parse_plain_decimal(const char* p, const char* last, double* value) {
  static_assert(FLT_EVAL_METHOD == 0, "the division must round once, in double");
  static constexpr double kPowersOf10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                           1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                           1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
  constexpr int kMaxDigits = 19;    // any 19 digits fit in 64 bits
  constexpr int kMaxFraction = 22;  // 10^22 is the largest power of 10 a double holds exactly
  constexpr uint64_t kMaxExact = uint64_t{1} << 53;
  const bool negative = p != last && *p == '-';
  if (negative) ++p;
  uint64_t m = 0;
  int digits = 0;
  const char* const integer = p;
  for (; p != last && static_cast<unsigned>(*p - '0') < 10; ++p, ++digits)
    m = 10 * m + static_cast<unsigned>(*p - '0');  // wraps past 19 digits: refused below
  const bool has_integer = p != integer;
  int fraction = 0;
  if (p != last && *p == '.') {
    const char* const start = ++p;
    for (; p != last && static_cast<unsigned>(*p - '0') < 10; ++p, ++digits)
      m = 10 * m + static_cast<unsigned>(*p - '0');
    fraction = static_cast<int>(p - start);
    if (!has_integer && fraction == 0) return nullptr;  // "." or "-."
  } else if (!has_integer) {
    return nullptr;  // "inf", "nan", "-", ...
  }
  if (p != last && (*p == 'e' || *p == 'E')) return nullptr;
  if (digits > kMaxDigits || m > kMaxExact || fraction > kMaxFraction) return nullptr;
  const double v = static_cast<double>(m) / kPowersOf10[fraction];
  *value = negative ? -v : v;
  return p;
}

// Parses the number that starts at `first` (a leading '+' allowed, as strtod does) and returns
// where it stops, or nullptr when no number starts there. Locale-independent. A value too small
// for a double reads as a signed zero, as strtod gives; one too large reads as infinity, which
// the callers refuse as not finite.
const char* parse_number(const char* first, const char* last, double* value) {
  const char* p = first;
  if (p != last && *p == '+') {
    ++p;
    if (p != last && (*p == '-' || *p == '+')) return nullptr;
  }
  if (const char* stop = parse_plain_decimal(p, last, value)) return stop;
  const auto r = std::from_chars(p, last, *value);
  if (r.ec == std::errc::result_out_of_range) {
    // Underflow has a negative exponent; "1e-400" is zero, "1e400" is not a finite number.
    const char* e = p;
    while (e != r.ptr && *e != 'e' && *e != 'E') ++e;
    const bool underflow = e + 1 < r.ptr && e[1] == '-';
    *value = underflow ? (*p == '-' ? -0.0 : 0.0) : (*p == '-' ? -HUGE_VAL : HUGE_VAL);
    return r.ptr;
  }
  if (r.ec != std::errc()) return nullptr;
  return r.ptr;
}

// Parses a whole token as a double.
bool parse_double(std::string_view token, double* value) {
  const char* last = token.data() + token.size();
  return !token.empty() && parse_number(token.data(), last, value) == last;
}

// A token cut off by the end of the file: only characters a number can hold ("-1.5e").
bool looks_like_cut_number(std::string_view token) {
  for (char c : token) {
    if (!std::isdigit(static_cast<unsigned char>(c)) && c != '+' && c != '-' && c != '.' &&
        c != 'e' && c != 'E')
      return false;
  }
  return !token.empty();
}

bool parse_channel(std::string_view token, Channel* channel) {
  static const struct {
    const char* name;
    Channel channel;
  } kNames[] = {{"Xposition", Channel::kXposition}, {"Yposition", Channel::kYposition},
                {"Zposition", Channel::kZposition}, {"Xrotation", Channel::kXrotation},
                {"Yrotation", Channel::kYrotation}, {"Zrotation", Channel::kZrotation}};
  for (const auto& n : kNames) {
    if (iequals(token, n.name)) {
      *channel = n.channel;
      return true;
    }
  }
  return false;
}

// Walks the text line by line, tracking 1-based line numbers. LF, CRLF and CR all end a line.
class LineReader {
 public:
  explicit LineReader(std::string_view text) : text_(text) {}

  bool at_end() const { return pos_ >= text_.size(); }
  // Line numbers are 64-bit: a file under the memory limit can have more than 2^31 lines.
  long long line() const { return line_; }            // line number of the line last returned
  long long next_line() const { return next_line_; }  // line number of the line at position()
  size_t position() const { return pos_; }
  size_t remaining() const { return text_.size() - pos_; }
  std::string_view text() const { return text_; }

  std::string_view next() {
    const size_t start = pos_;
    size_t p = pos_;
    while (p < text_.size() && !is_eol(text_[p])) ++p;
    std::string_view line = text_.substr(start, p - start);
    if (p < text_.size()) {
      if (text_[p] == '\r' && p + 1 < text_.size() && text_[p + 1] == '\n') ++p;
      ++p;
    }
    pos_ = p;
    line_ = next_line_++;
    return line;
  }

  // The next line that is not blank; an empty view at the end of the input, with line() then
  // the last line of the file (where a message about a cut file should point).
  std::string_view next_nonblank() {
    while (!at_end()) {
      std::string_view l = trim(next());
      if (!l.empty()) return l;
    }
    line_ = std::max(1LL, next_line_ - 1);
    return {};
  }

 private:
  std::string_view text_;
  size_t pos_ = 0;
  long long line_ = 0;
  long long next_line_ = 1;
};

// Splits off the first whitespace-separated word.
std::string_view first_word(std::string_view line, std::string_view* rest) {
  size_t i = 0;
  while (i < line.size() && !is_space(line[i])) ++i;
  if (rest) *rest = trim(line.substr(i));
  return line.substr(0, i);
}

// "Frames: 12", "FRAME TIME:\t0.03", "Frames 12": matches a key of one or more words, any case,
// any spacing, optional colon. Returns false when the line is not that key.
bool match_key(std::string_view line, std::initializer_list<std::string_view> words,
               std::string_view* value) {
  for (std::string_view word : words) {
    line = trim(line);
    if (line.size() < word.size() || !iequals(line.substr(0, word.size()), word)) return false;
    line.remove_prefix(word.size());
  }
  // The key must end here: "Framesx" is not "Frames".
  if (!line.empty() && line.front() != ':' && !is_space(line.front())) return false;
  line = trim(line);
  if (!line.empty() && line.front() == ':') line.remove_prefix(1);
  *value = trim(line);
  return true;
}

class Parser {
 public:
  Parser(std::string_view text, const std::string& source, std::vector<std::string>* warnings,
         const BvhReadOptions& options)
      : reader_(text), source_(source), warnings_(warnings), options_(options) {}

  Clip run() {
    Clip clip;
    clip.source = source_;
    parse_hierarchy(&clip.skeleton);
    parse_motion(&clip);
    return clip;
  }

 private:
  [[noreturn]] void fail(long long line, const std::string& what) const {
    throw InputError(source_ + ":" + std::to_string(line) + ": " + what);
  }
  [[noreturn]] void expected(const std::string& what, std::string_view found) const {
    fail(reader_.line(), "expected " + what + ", found " +
                             (reader_.at_end() && found.empty() ? std::string("end of file")
                                                                : shown(found)));
  }
  void warn(long long line, const std::string& what) {
    if (warnings_) warnings_->push_back(source_ + ":" + std::to_string(line) + ": " + what);
  }

  struct Open {
    int joint;
    bool has_offset = false;
    bool has_channels = false;
    bool has_children = false;
  };

  void parse_hierarchy(Skeleton* skeleton) {
    std::string_view line = reader_.next_nonblank();
    if (line.empty()) fail(1, "expected HIERARCHY, found an empty file");
    // A UTF-8 byte order mark, as some Windows editors write.
    if (line.substr(0, 3) == "\xEF\xBB\xBF") line = trim(line.substr(3));
    std::string_view rest;
    std::string_view word = first_word(line, &rest);
    if (!iequals(word, "HIERARCHY")) expected("HIERARCHY", word);
    if (!rest.empty()) expected("end of line after HIERARCHY", rest);

    std::vector<Open> stack;  // joints whose '{' is open, innermost last
    bool need_brace = false;  // a ROOT/JOINT/End Site line was read, its '{' not yet
    for (;;) {
      line = reader_.next_nonblank();
      if (line.empty()) {
        expected(need_brace        ? "'{'"
                 : !stack.empty()  ? (stack.back().has_offset ? "'}'" : "OFFSET")
                 : skeleton->joints.empty() ? "ROOT"
                                            : "MOTION",
                 line);
      }
      word = first_word(line, &rest);
      if (need_brace) {
        if (word != "{") expected("'{'", word);
        if (!rest.empty()) expected("end of line after '{'", rest);
        stack.push_back({static_cast<int>(skeleton->joints.size()) - 1});
        need_brace = false;
        continue;
      }
      if (stack.empty()) {
        if (iequals(word, "MOTION")) {
          if (skeleton->joints.empty()) expected("ROOT", word);
          if (!rest.empty()) expected("end of line after MOTION", rest);
          break;
        }
        if (!iequals(word, "ROOT")) expected(skeleton->joints.empty() ? "ROOT" : "ROOT or MOTION", word);
        open_joint(skeleton, -1, rest, false, &stack, &need_brace);
        continue;
      }
      Open& open = stack.back();
      Joint& joint = skeleton->joints[open.joint];
      if (word == "}") {
        if (!rest.empty()) expected("end of line after '}'", rest);
        if (!open.has_offset) expected("OFFSET in " + describe(joint), word);
        stack.pop_back();
      } else if (iequals(word, "OFFSET")) {
        if (open.has_offset) fail(reader_.line(), describe(joint) + " has a second OFFSET");
        if (open.has_children) expected("JOINT, End Site or '}'", word);
        parse_offset(rest, &joint);
        open.has_offset = true;
      } else if (iequals(word, "CHANNELS")) {
        if (joint.end_site) expected("OFFSET or '}' in an End Site", word);
        if (open.has_channels) fail(reader_.line(), describe(joint) + " has a second CHANNELS");
        if (open.has_children) expected("JOINT, End Site or '}'", word);
        parse_channels(rest, &joint, skeleton);
        open.has_channels = true;
      } else if (iequals(word, "JOINT") || iequals(word, "End")) {
        if (joint.end_site) expected("'}' closing the End Site", word);
        if (!open.has_offset) expected("OFFSET in " + describe(joint), word);
        open.has_children = true;
        const bool end_site = iequals(word, "End");
        if (end_site) {
          std::string_view site_rest;
          std::string_view site = first_word(rest, &site_rest);
          if (!iequals(site, "Site")) expected("'Site' after End", site);
          rest = site_rest;
        }
        const int parent = open.joint;
        open_joint(skeleton, parent, rest, end_site, &stack, &need_brace);
      } else {
        expected(open.has_offset ? "CHANNELS, JOINT, End Site or '}'" : "OFFSET", word);
      }
    }
  }

  std::string describe(const Joint& joint) const {
    return joint.end_site ? "the End Site of '" + skeleton_name_of_parent(joint) + "'"
                          : "joint '" + joint.name + "'";
  }
  std::string skeleton_name_of_parent(const Joint& joint) const {
    const std::string suffix = " End Site";
    return joint.name.size() > suffix.size() ? joint.name.substr(0, joint.name.size() - suffix.size())
                                             : joint.name;
  }

  // Adds a joint from the rest of its ROOT/JOINT/End Site line. Its '{' may end that line
  // ("JOINT Hips {") or come on the next one (then *need_brace is set).
  void open_joint(Skeleton* skeleton, int parent, std::string_view rest, bool end_site,
                  std::vector<Open>* stack, bool* need_brace) {
    bool opened = false;
    if (!rest.empty() && rest.back() == '{') {
      rest = trim(rest.substr(0, rest.size() - 1));
      opened = true;
    }
    Joint joint;
    joint.parent = parent;
    joint.end_site = end_site;
    joint.line = static_cast<int>(std::min<long long>(reader_.line(), INT_MAX));
    if (end_site) {
      // Some exporters name End Sites ("End Site LeftToe_end"); Blender ignores the name, so do we.
      joint.name = skeleton->joints[parent].name + " End Site";
    } else {
      if (rest.empty()) fail(reader_.line(), "expected a joint name, found end of line");
      // "ROOT Hips {{": no BVH text can hold a name ending in '{' (it reads as the brace), so
      // the writer could not write it back; with the brace on the next line it fails already.
      if (rest.back() == '{') expected("a joint name not ending in '{'", rest);
      joint.name = std::string(rest);
    }
    joint.first_channel = skeleton->channel_count;
    skeleton->joints.push_back(std::move(joint));
    if (opened) stack->push_back({static_cast<int>(skeleton->joints.size()) - 1});
    *need_brace = !opened;
  }

  void parse_offset(std::string_view rest, Joint* joint) {
    double v[3] = {0, 0, 0};
    int count = 0;
    while (!rest.empty()) {
      std::string_view token = first_word(rest, &rest);
      if (count < 3 && (!parse_double(token, &v[count]) || !std::isfinite(v[count])))
        expected("a finite number in OFFSET of " + describe(*joint), token);
      ++count;
    }
    if (count != 3)
      fail(reader_.line(), "expected 3 numbers after OFFSET of " + describe(*joint) + ", found " +
                               std::to_string(count));
    joint->offset = Eigen::Vector3d(v[0], v[1], v[2]);
  }

  void parse_channels(std::string_view rest, Joint* joint, Skeleton* skeleton) {
    std::string_view count_token = first_word(rest, &rest);
    long long count = -1;
    auto r = std::from_chars(count_token.data(), count_token.data() + count_token.size(), count);
    if (r.ec != std::errc() || r.ptr != count_token.data() + count_token.size() || count < 0 ||
        count > kMaxChannelsPerJoint)
      expected("a channel count from 0 to 6 after CHANNELS", count_token);
    std::vector<Channel> channels;
    while (!rest.empty()) {
      std::string_view token = first_word(rest, &rest);
      Channel c;
      if (!parse_channel(token, &c))
        expected("a channel name (Xposition .. Zrotation) for " + describe(*joint), token);
      if (std::find(channels.begin(), channels.end(), c) != channels.end())
        fail(reader_.line(), describe(*joint) + " lists channel " + channel_name(c) + " twice");
      channels.push_back(c);  // at most 6: a seventh name repeats one
    }
    if (static_cast<long long>(channels.size()) != count)
      fail(reader_.line(), "expected " + std::to_string(count) + " channel names for " +
                               describe(*joint) + ", found " + std::to_string(channels.size()));
    joint->channels = std::move(channels);
    joint->first_channel = skeleton->channel_count;
    skeleton->channel_count += static_cast<int>(count);
  }

  void parse_motion(Clip* clip) {
    std::string_view value;
    std::string_view line = reader_.next_nonblank();
    if (!match_key(line, {"Frames"}, &value)) expected("'Frames: N'", first_word(line, nullptr));
    const long long frames_line = reader_.line();
    long long declared = -1;
    auto r = std::from_chars(value.data(), value.data() + value.size(), declared);
    if (value.empty()) expected("a frame count after Frames:", value);
    if (r.ec == std::errc::result_out_of_range && r.ptr == value.data() + value.size())
      declared = value.front() == '-' ? -1 : kMaxFrames + 1;
    else if (r.ec != std::errc() || r.ptr != value.data() + value.size())
      expected("a whole frame count after Frames:", value);
    if (declared < 0) fail(frames_line, "expected a frame count of 0 or more, found " + shown(value));
    if (declared > kMaxFrames)
      fail(frames_line, "expected a frame count of at most " + std::to_string(kMaxFrames) +
                            ", found " + shown(value));

    line = reader_.next_nonblank();
    if (!match_key(line, {"Frame", "Time"}, &value))
      expected("'Frame Time: seconds'", first_word(line, nullptr));
    double frame_time = 0;
    if (!parse_double(value, &frame_time) || !std::isfinite(frame_time) || frame_time <= 0)
      expected("a positive frame time in seconds", value);
    clip->frame_time = frame_time;

    if (clip->skeleton.channel_count == 0) {
      parse_empty_frames(clip, declared, frames_line);
    } else {
      parse_frames(clip, declared, frames_line);
    }
  }

  // The frame lines: one pass over the bytes, numbers parsed straight into the matrix, no
  // per-line or per-value allocation. This loop is the parser's hot path (tests/bench/bvh_bench).
  void parse_frames(Clip* clip, long long declared, long long frames_line) {
    const int channels = clip->skeleton.channel_count;
    const std::string_view text = reader_.text();
    const char* p = text.data() + reader_.position();
    const char* const end = text.data() + text.size();
    long long line = reader_.next_line();
    const size_t row_bytes = sizeof(double) * static_cast<size_t>(channels);
    const Eigen::Index max_rows = static_cast<Eigen::Index>(options_.max_bytes / row_bytes);
    Eigen::Index capacity = frame_capacity(declared, frames_line, channels, max_rows);
    MotionMatrix motion(capacity, channels);
    advise_huge_pages(motion.data(), static_cast<size_t>(capacity) * row_bytes);
    Eigen::Index frames = 0;
    long long cut_line = 0;  // line of a short frame line; only the last line may be one
    long long last_line = frames_line + 1;  // the last line holding values (Frame Time: before any)
    int cut_count = 0;       // values on it
    while (p < end) {
      const long long line_number = line;
      double* row = nullptr;
      int count = 0;
      bool cut_token = false;
      for (;;) {
        while (p < end && is_space(*p)) ++p;
        if (p == end || is_eol(*p)) break;
        const char* token = p;
        if (count == channels) fail_extra_values(p, end, line_number, channels, frames);
        double v;
        const char* stop = parse_number(token, end, &v);
        if (stop == nullptr || (stop != end && !is_separator(*stop)) || !std::isfinite(v)) {
          p = cut_number_end(clip, token, stop, end, line_number, frames, count);
          cut_token = true;
          break;
        }
        if (count == 0) {
          if (frames == capacity) grow_frames(motion, capacity, frames, token, end, line_number, max_rows);
          row = motion.data() + frames * channels;
        }
        row[count++] = v;
        p = stop;
      }
      if (p < end) {  // the line's end: CRLF, LF or CR
        if (*p == '\r' && p + 1 < end && p[1] == '\n') ++p;
        ++p;
        ++line;
      }
      if (count == 0 && !cut_token) continue;  // blank line
      last_line = line_number;
      if (cut_line != 0) {
        // A short line followed by more data was not the cut last line: refuse it.
        fail(cut_line, "expected " + std::to_string(channels) + " values in frame " +
                           std::to_string(frames + 1) + ", found " + std::to_string(cut_count));
      }
      if (count < channels) {
        cut_line = line_number;
        cut_count = count;
        continue;
      }
      ++frames;
    }
    if (frames != capacity) motion.conservativeResize(frames, channels);
    clip->motion = std::move(motion);
    check_frame_count(channels, declared, frames_line, frames, last_line, cut_line, cut_count);
  }

  // The frames to allocate at first: never from the declared count alone, as the text bounds how
  // many frames it holds. Fails (on the Frames: line) beyond the memory limit, max_rows rows.
  Eigen::Index frame_capacity(long long declared, long long frames_line, int channels, Eigen::Index max_rows) const {
    // Products of counts stay below the text's size: no overflow.
    const long long affordable =
        static_cast<long long>(reader_.remaining() / kMinBytesPerValue / channels) + 1;
    const Eigen::Index capacity = static_cast<Eigen::Index>(std::min(declared, affordable));
    if (capacity > max_rows) {
      const size_t needed = static_cast<size_t>(capacity) * sizeof(double) * static_cast<size_t>(channels);
      fail(frames_line, "expected frames within the memory limit of " +
                            describe_bytes(options_.max_bytes) + ", found Frames: " +
                            std::to_string(declared) + " of " + std::to_string(channels) +
                            " values each (" + describe_bytes(needed) +
                            (declared > affordable ? " for the frames this file can hold)" : ")"));
    }
    return capacity;
  }

  // More frames than declared: the matrix grown geometrically, within what the rest of the text
  // (from token) can hold and the memory limit (max_rows), or a failure on the line.
  void grow_frames(MotionMatrix& motion, Eigen::Index& capacity, Eigen::Index frames, const char* token,
                   const char* end, long long line_number, Eigen::Index max_rows) const {
    const Eigen::Index channels = motion.cols();
    const size_t row_bytes = sizeof(double) * static_cast<size_t>(channels);
    const Eigen::Index left =
        static_cast<Eigen::Index>(static_cast<size_t>(end - token) / kMinBytesPerValue / channels) + 1;
    capacity = std::min({std::max<Eigen::Index>(2 * capacity, 64), frames + left, max_rows});
    if (capacity <= frames) {
      const size_t needed = static_cast<size_t>(frames + 1) * row_bytes;
      fail(line_number, "expected frames within the memory limit of " + describe_bytes(options_.max_bytes) +
                            ", found frame " + std::to_string(frames + 1) + " of " + std::to_string(channels) +
                            " values (" + describe_bytes(needed) + ")");
    }
    MotionMatrix grown(capacity, channels);
    advise_huge_pages(grown.data(), static_cast<size_t>(capacity) * row_bytes);
    grown.topRows(frames) = motion.topRows(frames);
    motion.swap(grown);
  }

  // A value beyond the channels at p: fails, counting the line's values.
  [[noreturn]] void fail_extra_values(const char* p, const char* end, long long line_number, int channels,
                                      Eigen::Index frames) const {
    int extra = 0;
    while (p < end && !is_eol(*p)) {
      while (p < end && is_space(*p)) ++p;
      if (p == end || is_eol(*p)) break;
      ++extra;
      while (p < end && !is_separator(*p)) ++p;
    }
    fail(line_number, "expected " + std::to_string(channels) + " values in frame " + std::to_string(frames + 1) +
                          ", found " + std::to_string(channels + extra));
  }

  // A token at `token` that is no finite number (parse_number stopped at stop): where the file
  // ends inside it ("-1.5e"), a cut last line, whose end is returned; anything else fails.
  const char* cut_number_end(const Clip* clip, const char* token, const char* stop, const char* end,
                             long long line_number, Eigen::Index frames, int count) const {
    const char* token_end = token;
    while (token_end < end && !is_separator(*token_end)) ++token_end;
    const std::string_view bad(token, token_end - token);
    if (token_end == end && looks_like_cut_number(bad) && (stop == nullptr || stop != end)) return token_end;
    fail(line_number, "expected a finite number for frame " + std::to_string(frames + 1) + " channel " +
                          std::to_string(count + 1) + " (" + channel_label(clip->skeleton.joints, count) +
                          "), found " + shown(bad));
  }

  // Warnings for a cut last line and for a frame count other than the declared one.
  // Fewer frames than Frames: declares is a file cut short (a copy or an export that stopped):
  // refused, as a part of a take would be aligned and styled as if it were the whole. More frames
  // than declared lose nothing: loaded, with a warning.
  void check_frame_count(int channels, long long declared, long long frames_line, Eigen::Index frames,
                         long long last_line, long long cut_line, int cut_count) {
    if (frames < declared) {
      const std::string cut = cut_line != 0 ? ", its last line cut (" + std::to_string(cut_count) + " of " +
                                                  std::to_string(channels) + " values)"
                                            : std::string();
      fail(last_line, "the file ends after " + std::to_string(frames) + " complete frame" + (frames == 1 ? "" : "s") +
                          " of the " + std::to_string(declared) + " that Frames: declares on line " +
                          std::to_string(frames_line) + cut + ": it was cut short; copy or export it again (or set " +
                          "Frames: to " + std::to_string(frames) + " to load what is there)");
    }
    if (cut_line != 0) {
      warn(cut_line, "the last frame line is cut (" + std::to_string(cut_count) + " of " +
                         std::to_string(channels) + " values); loaded the " +
                         std::to_string(frames) + " complete frames");
    }
    if (frames != declared) {
      warn(frames_line, "Frames: says " + std::to_string(declared) + " but the file has " +
                            std::to_string(frames) + " complete frames; loaded " +
                            std::to_string(frames));
    }
  }

  // A skeleton without channels: each frame is an empty line, so count lines, never trusting
  // the declared count beyond what the text holds.
  void parse_empty_frames(Clip* clip, long long declared, long long frames_line) {
    long long lines = 0;
    while (!reader_.at_end()) {
      const std::string_view l = trim(reader_.next());
      if (!l.empty())
        fail(reader_.line(), "expected 0 values in frame " + std::to_string(lines + 1) +
                                 ", found " + shown(first_word(l, nullptr)));
      if (lines < declared) ++lines;  // blank lines past the declared count are just blank
    }
    if (lines != declared) {  // blank lines past the count are blank; fewer: the file was cut short
      fail(reader_.line(), "the file ends after " + std::to_string(lines) + " frame line" + (lines == 1 ? "" : "s") +
                               " of the " + std::to_string(declared) + " that Frames: declares on line " +
                               std::to_string(frames_line) + ": it was cut short; copy or export it again (or set " +
                               "Frames: to " + std::to_string(lines) + " to load what is there)");
    }
    clip->motion.resize(static_cast<Eigen::Index>(lines), 0);
  }

  static std::string channel_label(const std::vector<Joint>& joints, int channel) {
    for (const Joint& j : joints) {
      const int local = channel - j.first_channel;
      if (!j.end_site && local >= 0 && local < static_cast<int>(j.channels.size()))
        return j.name + " " + channel_name(j.channels[local]);
    }
    return "?";
  }

  LineReader reader_;
  const std::string& source_;
  std::vector<std::string>* warnings_;
  const BvhReadOptions& options_;
};

}  // namespace

Clip parse_bvh(std::string_view text, const std::string& source,
               std::vector<std::string>* warnings, const BvhReadOptions& options) {
  return Parser(text, source, warnings, options).run();
}

Clip read_bvh_file(const std::string& path, std::vector<std::string>* warnings,
                   const BvhReadOptions& options) {
  const std::string text = read_file(path, options.max_bytes);
  return parse_bvh(text, path, warnings, options);
}

}  // namespace mostyle
