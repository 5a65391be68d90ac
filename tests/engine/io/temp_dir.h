#pragma once
// A folder of a test's own under the system's temporary folder, removed with what it holds when
// the test is done: the format tests write files there and read them back.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace mostyle::test {

class TempDir {
 public:
  TempDir() : dir_(std::filesystem::temp_directory_path() / name()) { std::filesystem::create_directories(dir_); }
  ~TempDir() { std::filesystem::remove_all(dir_); }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  std::string path(const std::string& file) const { return (dir_ / file).string(); }
  // Writes `bytes` as `file` in the folder; returns its path.
  std::string write(const std::string& file, const std::string& bytes) const {
    std::ofstream(dir_ / file, std::ios::binary) << bytes;
    return path(file);
  }

 private:
  // Unique within the machine (the process) and the process (a count).
  static std::string name() {
    static int made = 0;
    return "mostyle_test_" + std::to_string(::getpid()) + "_" + std::to_string(made++);
  }

  std::filesystem::path dir_;
};

}  // namespace mostyle::test
