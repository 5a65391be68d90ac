#include "engine/io/bvh/bvh_write.h"

#include <algorithm>
#include <charconv>
#include <string>
#include <vector>

#include "engine/base/atomic_file.h"

namespace mostyle {
namespace {

// Shortest text that reads back as the same double.
void append_number(std::string* out, double v) {
  char buffer[32];
  auto r = std::to_chars(buffer, buffer + sizeof buffer, v);
  out->append(buffer, r.ptr);
}

constexpr int kMaxIndent = 32;  // deep files stay linear in size

void append_indent(std::string* out, int depth) { out->append(std::min(depth, kMaxIndent), '\t'); }

bool has_position_channel(const Joint& j) {
  return std::any_of(j.channels.begin(), j.channels.end(), [](Channel c) { return is_position(c); });
}

}  // namespace

std::string format_bvh_hierarchy(const Skeleton& s) {
  std::string out;
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
    // A root's position channels place it alone (Blender and we ignore its OFFSET); three.js
    // adds the OFFSET to them. A zero OFFSET there is read the same by all three.
    const bool moot_offset = j.parent < 0 && has_position_channel(j);
    for (int d = 0; d < 3; ++d) {
      out += ' ';
      append_number(&out, moot_offset ? 0.0 : j.offset[d]);
    }
    out += '\n';
    if (!j.end_site) {
      append_indent(&out, depth[i] + 1);
      out += "CHANNELS ";
      out += std::to_string(j.channels.size());
      for (Channel c : j.channels) {
        out += ' ';
        out += channel_name(c);
      }
      out += '\n';
    }
    open.push_back(i);
  }
  close_until(-1);
  return out;
}

std::string format_bvh(const Clip& clip) {
  std::string out;
  out.reserve(4096 + static_cast<size_t>(clip.motion.size()) * 12);
  out += format_bvh_hierarchy(clip.skeleton);
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
