#include "app/cli/cli_common.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdlib>
#include <filesystem>
#include <iostream>

#include "engine/base/atomic_file.h"
#include "engine/io/bvh/bvh_read.h"
#include "engine/base/error.h"
#include "engine/base/memory_limit.h"
#include "engine/io/motion_file.h"

namespace mostyle::cli {

std::string number(double v) {
  char buffer[32];
  auto r = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, r.ptr);
}

void write_output(const std::string& path, const std::string& content) {
  write_file_atomically(path, content);
}

std::string positions_csv(const Eigen::MatrixXd& positions, const std::vector<int>& joints,
                          const std::vector<std::string>& names) {
  std::string csv = "frame,joint,x,y,z\n";
  csv.reserve(static_cast<size_t>(positions.rows() * joints.size()) * 48);
  for (Eigen::Index f = 0; f < positions.rows(); ++f) {
    const std::string frame = std::to_string(f);
    for (size_t i = 0; i < joints.size(); ++i) {
      csv += frame;
      csv += ',';
      // RFC 4180: a joint name with a comma or a quote is quoted, its quotes doubled.
      if (names[i].find_first_of(",\"") == std::string::npos) {
        csv += names[i];
      } else {
        csv += '"';
        for (char c : names[i]) csv += c == '"' ? std::string("\"\"") : std::string(1, c);
        csv += '"';
      }
      for (int d = 0; d < 3; ++d) {
        csv += ',';
        csv += number(positions(f, 3 * joints[i] + d));
      }
      csv += '\n';
    }
  }
  return csv;
}

size_t memory_limit_from_environment() {
  const char* text = std::getenv(kMemoryLimitVariable);
  return parse_memory_limit(text ? text : "");
}

BvhReadOptions bvh_read_options_from_environment() {
  BvhReadOptions options;
  options.max_bytes = memory_limit_from_environment();
  return options;
}

MotionReadOptions motion_read_options_from_environment() {
  MotionReadOptions options;
  options.max_bytes = bvh_read_options_from_environment().max_bytes;
  return options;
}

Clip load_clip(const std::string& path, const std::string& take, double fps) {
  std::vector<std::string> warnings, notes;
  MotionReadOptions options = motion_read_options_from_environment();
  options.take = take;
  options.fps = fps;
  Clip clip = read_motion_file(path, &warnings, options, &notes);
  for (const std::string& w : warnings) std::cerr << "mostyle: warning: " << w << "\n";
  for (const std::string& n : notes) std::cerr << "mostyle: note: " << n << "\n";
  return clip;
}

const CLI::Validator& written_motion_format() {
  static const CLI::Validator check(
      [](std::string& path) -> std::string {
        if (is_written_motion_path(path)) return "";
        return "cannot write '" + path + "': the formats written are " + kWrittenMotionFormats;
      },
      "BVH, FBX or glTF", "motion file to write");
  return check;
}

}  // namespace mostyle::cli
