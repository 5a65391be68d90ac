#include "engine/bvh_io.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <string>

#include "engine/atomic_file.h"
#include "engine/error.h"

namespace mostyle {
namespace {

// Limits that keep a hostile file from allocating or running away.
constexpr long long kMaxFrames = 100'000'000;  // more than a day at 1000 fps
constexpr int kMaxChannelsPerJoint = 6;
constexpr size_t kShownTokenLength = 40;

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\f' || c == '\v'; }
bool is_eol(char c) { return c == '\n' || c == '\r'; }

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
  if (token.empty()) return "end of line";
  std::string out = "'";
  for (size_t i = 0; i < token.size() && i < kShownTokenLength; ++i) {
    const unsigned char c = static_cast<unsigned char>(token[i]);
    if (c >= 32 && c < 127) {
      out += static_cast<char>(c);
    } else {
      static const char* kHex = "0123456789abcdef";
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 15];
    }
  }
  if (token.size() > kShownTokenLength) out += "...";
  return out + "'";
}

// Parses a whole token as a double (a leading '+' allowed, as strtod does).
bool parse_double(std::string_view token, double* value) {
  const char* first = token.data();
  const char* last = first + token.size();
  if (first != last && *first == '+') ++first;
  if (first == last) return false;
  auto result = std::from_chars(first, last, *value);
  return result.ec == std::errc() && result.ptr == last;
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
  int line() const { return line_; }  // line number of the line last returned
  size_t position() const { return pos_; }
  size_t remaining() const { return text_.size() - pos_; }

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

  // The next line that is not blank; empty view at end of input.
  std::string_view next_nonblank() {
    while (!at_end()) {
      std::string_view l = trim(next());
      if (!l.empty()) return l;
    }
    line_ = next_line_;
    return {};
  }

 private:
  std::string_view text_;
  size_t pos_ = 0;
  int line_ = 0;
  int next_line_ = 1;
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
  Parser(std::string_view text, const std::string& source, std::vector<std::string>* warnings)
      : reader_(text), source_(source), warnings_(warnings) {}

  Clip run() {
    Clip clip;
    clip.source = source_;
    parse_hierarchy(&clip.skeleton);
    parse_motion(&clip);
    return clip;
  }

 private:
  [[noreturn]] void fail(int line, const std::string& what) const {
    throw InputError(source_ + ":" + std::to_string(line) + ": " + what);
  }
  [[noreturn]] void expected(const std::string& what, std::string_view found) const {
    fail(reader_.line(), "expected " + what + ", found " +
                             (reader_.at_end() && found.empty() ? std::string("end of file")
                                                                : shown(found)));
  }
  void warn(const std::string& what) {
    if (warnings_) warnings_->push_back(source_ + ": " + what);
  }

  struct Open {
    int joint;
    bool has_offset = false;
    bool has_channels = false;
    bool has_children = false;
  };

  void parse_hierarchy(Skeleton* skeleton) {
    std::string_view line = reader_.next_nonblank();
    if (line.empty() && reader_.at_end()) fail(reader_.line() ? reader_.line() : 1, "expected HIERARCHY, found an empty file");
    std::string_view rest;
    std::string_view word = first_word(line, &rest);
    if (!iequals(word, "HIERARCHY")) expected("HIERARCHY", word);
    if (!rest.empty()) expected("end of line after HIERARCHY", rest);

    std::vector<Open> stack;  // joints whose '{' is open, innermost last
    bool need_brace = false;  // a ROOT/JOINT/End Site line was read, its '{' not yet
    for (;;) {
      line = reader_.next_nonblank();
      if (line.empty()) {
        expected(stack.empty() && !need_brace ? (skeleton->joints.empty() ? "ROOT" : "MOTION")
                                              : (need_brace ? "'{'" : "'}'"),
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
    joint.line = reader_.line();
    if (end_site) {
      if (!rest.empty()) expected("'{' after End Site", rest);
      joint.name = skeleton->joints[parent].name + " End Site";
    } else {
      if (rest.empty()) fail(reader_.line(), "expected a joint name, found end of line");
      joint.name = std::string(rest);
    }
    joint.first_channel = skeleton->channel_count;
    skeleton->joints.push_back(std::move(joint));
    if (opened) stack->push_back({static_cast<int>(skeleton->joints.size()) - 1});
    *need_brace = !opened;
  }

  void parse_offset(std::string_view rest, Joint* joint) {
    double v[3];
    int count = 0;
    while (!rest.empty()) {
      std::string_view token = first_word(rest, &rest);
      if (count == 3) expected("3 numbers after OFFSET", token);
      if (!parse_double(token, &v[count]) || !std::isfinite(v[count]))
        expected("a finite number in OFFSET of " + describe(*joint), token);
      ++count;
    }
    if (count < 3)
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
      channels.push_back(c);
    }
    if (static_cast<long long>(channels.size()) != count)
      fail(reader_.line(), "expected " + std::to_string(count) + " channel names for " +
                               describe(*joint) + ", found " + std::to_string(channels.size()));
    joint->channels = std::move(channels);
    joint->first_channel = skeleton->channel_count;
    skeleton->channel_count += static_cast<int>(count);
  }

  void parse_motion(Clip* clip) {
    const int channels = clip->skeleton.channel_count;
    std::string_view value;
    std::string_view line = reader_.next_nonblank();
    if (!match_key(line, {"Frames"}, &value)) expected("'Frames: N'", first_word(line, nullptr));
    long long declared = -1;
    auto r = std::from_chars(value.data(), value.data() + value.size(), declared);
    if (value.empty() || r.ec == std::errc::result_out_of_range)
      expected("a frame count after Frames:", value);
    if (r.ec != std::errc() || r.ptr != value.data() + value.size())
      expected("a whole frame count after Frames:", value);
    if (declared < 0) fail(reader_.line(), "expected a frame count of 0 or more, found " + shown(value));
    if (declared > kMaxFrames)
      fail(reader_.line(), "expected a frame count of at most " + std::to_string(kMaxFrames) +
                               ", found " + shown(value));

    line = reader_.next_nonblank();
    if (!match_key(line, {"Frame", "Time"}, &value))
      expected("'Frame Time: seconds'", first_word(line, nullptr));
    double frame_time = 0;
    if (!parse_double(value, &frame_time) || !std::isfinite(frame_time) || frame_time <= 0)
      expected("a positive frame time in seconds", value);
    clip->frame_time = frame_time;

    if (channels == 0) {
      // No values to read: each frame is an empty line, which blank-line tolerance cannot count.
      clip->motion.resize(declared, 0);
      return;
    }

    // Never allocate from the declared count alone: each value takes at least two bytes.
    const size_t affordable = reader_.remaining() / 2 / static_cast<size_t>(channels) + 1;
    std::vector<double> values;
    values.reserve(std::min<size_t>(static_cast<size_t>(declared), affordable) * channels);
    long long frames = 0;
    int cut_line = 0;
    int cut_count = 0;
    const std::vector<Joint>& joints = clip->skeleton.joints;
    while (!reader_.at_end()) {
      std::string_view raw = reader_.next();
      const char* p = raw.data();
      const char* end = p + raw.size();
      int count = 0;
      for (;;) {
        while (p < end && is_space(*p)) ++p;
        if (p == end) break;
        const char* token_start = p;
        while (p < end && !is_space(*p)) ++p;
        std::string_view token(token_start, p - token_start);
        if (count == channels) {
          int extra = 1;
          while (p < end) {
            while (p < end && is_space(*p)) ++p;
            if (p == end) break;
            ++extra;
            while (p < end && !is_space(*p)) ++p;
          }
          fail(reader_.line(), "expected " + std::to_string(channels) + " values in frame " +
                                   std::to_string(frames + 1) + ", found " +
                                   std::to_string(channels + extra));
        }
        double v;
        if (!parse_double(token, &v) || !std::isfinite(v)) {
          fail(reader_.line(), "expected a finite number for frame " + std::to_string(frames + 1) +
                                   " channel " + std::to_string(count + 1) + " (" +
                                   channel_label(joints, count) + "), found " + shown(token));
        }
        values.push_back(v);
        ++count;
      }
      if (count == 0) continue;  // blank line
      if (count < channels) {
        if (cut_line == 0) {
          cut_line = reader_.line();
          cut_count = count;
          values.resize(values.size() - count);
          continue;
        }
        break;
      }
      if (cut_line != 0) {
        fail(cut_line, "expected " + std::to_string(channels) + " values in frame " +
                           std::to_string(frames + 1) + ", found " + std::to_string(cut_count));
      }
      ++frames;
    }
    if (cut_line != 0) {
      warn(std::to_string(cut_line) + ": the last frame line is cut (" + std::to_string(cut_count) +
           " of " + std::to_string(channels) + " values); loaded the " + std::to_string(frames) +
           " complete frames");
    }
    if (frames != declared) {
      warn("declares " + std::to_string(declared) + " frames but has " + std::to_string(frames) +
           "; loaded " + std::to_string(frames));
    }
    clip->motion = Eigen::Map<MotionMatrix>(values.data(), frames, channels);
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
};

// Shortest text that reads back as the same double.
void append_number(std::string* out, double v) {
  char buffer[32];
  auto r = std::to_chars(buffer, buffer + sizeof buffer, v);
  out->append(buffer, r.ptr);
}

constexpr int kMaxIndent = 32;  // deep files stay linear in size

void append_indent(std::string* out, int depth) { out->append(std::min(depth, kMaxIndent), '\t'); }

}  // namespace

Clip parse_bvh(std::string_view text, const std::string& source,
               std::vector<std::string>* warnings) {
  return Parser(text, source, warnings).run();
}

Clip read_bvh_file(const std::string& path, std::vector<std::string>* warnings) {
  const std::string text = read_file(path);
  return parse_bvh(text, path, warnings);
}

std::string format_bvh(const Clip& clip) {
  const Skeleton& s = clip.skeleton;
  std::string out;
  out.reserve(4096 + static_cast<size_t>(clip.motion.size()) * 12);
  out += "HIERARCHY\n";
  std::vector<int> open;  // joints whose brace is open
  std::vector<int> depth(s.joints.size(), 0);
  auto close_until = [&](int parent) {
    while (!open.empty() && open.back() != parent) {
      append_indent(&out, depth[open.back()]);
      out += "}\n";
      open.pop_back();
    }
  };
  for (int i = 0; i < static_cast<int>(s.joints.size()); ++i) {
    const Joint& j = s.joints[i];
    close_until(j.parent);
    depth[i] = j.parent < 0 ? 0 : depth[j.parent] + 1;
    append_indent(&out, depth[i]);
    if (j.end_site) {
      out += "End Site\n";
    } else {
      out += j.parent < 0 ? "ROOT " : "JOINT ";
      out += j.name;
      out += '\n';
    }
    append_indent(&out, depth[i]);
    out += "{\n";
    append_indent(&out, depth[i] + 1);
    out += "OFFSET";
    for (int d = 0; d < 3; ++d) {
      out += ' ';
      append_number(&out, j.offset[d]);
    }
    out += '\n';
    if (!j.end_site) {
      append_indent(&out, depth[i] + 1);
      out += "CHANNELS " + std::to_string(j.channels.size());
      for (Channel c : j.channels) {
        out += ' ';
        out += channel_name(c);
      }
      out += '\n';
    }
    open.push_back(i);
  }
  close_until(-1);
  out += "MOTION\nFrames: " + std::to_string(clip.motion.rows()) + "\nFrame Time: ";
  append_number(&out, clip.frame_time);
  out += '\n';
  for (Eigen::Index f = 0; f < clip.motion.rows(); ++f) {
    for (Eigen::Index c = 0; c < clip.motion.cols(); ++c) {
      if (c) out += ' ';
      append_number(&out, clip.motion(f, c));
    }
    out += '\n';
  }
  return out;
}

void write_bvh_file(const Clip& clip, const std::string& path) {
  write_file_atomically(path, format_bvh(clip));
}

}  // namespace mostyle
