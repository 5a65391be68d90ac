#pragma once
// A scratch folder for tests that run the built mostyle-cli (MOSTYLE_CLI) as a user would.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace mostyle::test {

struct CliRun {
  int status = -1;       // exit status, -1 when the program did not exit normally
  std::string out, err;  // what it printed
};

inline std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A path or word in single quotes, for the shell line CliSandbox::cli runs (no ' inside).
inline std::string shell_quoted(const std::string& s) { return "'" + s + "'"; }

class CliSandbox {
 public:
  // A fresh folder named after `name` and this process, removed with the sandbox.
  explicit CliSandbox(const std::string& name)
      : dir_(std::filesystem::temp_directory_path() / (name + "_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  ~CliSandbox() { std::filesystem::remove_all(dir_); }
  CliSandbox(const CliSandbox&) = delete;
  CliSandbox& operator=(const CliSandbox&) = delete;

  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string write(const std::string& name, const std::string& content) const {
    std::ofstream(dir_ / name, std::ios::binary) << content;
    return path(name);
  }
  // Runs mostyle-cli with `args` (already quoted as needed) and collects exit status and output.
  CliRun cli(const std::string& args) const {
    const std::string out = path("stdout.txt"), err = path("stderr.txt");
    const std::string command = "\"" MOSTYLE_CLI "\" " + args + " >\"" + out + "\" 2>\"" + err + "\"";
    const int raw = std::system(command.c_str());
    CliRun r;
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    r.out = slurp(out);
    r.err = slurp(err);
    std::filesystem::remove(out);
    std::filesystem::remove(err);
    return r;
  }
  // Regular files in the folder: outputs and leftovers such as temporary files.
  int count_files() const {
    int n = 0;
    for (const auto& e : std::filesystem::directory_iterator(dir_)) n += e.is_regular_file();
    return n;
  }

 private:
  std::filesystem::path dir_;
};

}  // namespace mostyle::test
