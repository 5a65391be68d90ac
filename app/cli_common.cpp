#include "app/cli_common.h"

#include <charconv>

#include "engine/atomic_file.h"

namespace mostyle::cli {

std::string number(double v) {
  char buffer[32];
  auto r = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, r.ptr);
}

void write_output(const std::string& path, const std::string& content) {
  write_file_atomically(path, content);
}

}  // namespace mostyle::cli
