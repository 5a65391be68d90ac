#include "engine/base/atomic_file.h"

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "engine/base/error.h"

using namespace mostyle;
namespace fs = std::filesystem;

namespace {

struct TempFolder {
  fs::path dir = fs::temp_directory_path() / ("mostyle_atomic_file_test_" + std::to_string(::getpid()));
  TempFolder() { fs::create_directories(dir); }
  ~TempFolder() { fs::remove_all(dir); }
  std::string write(const std::string& name, const std::string& bytes) const {
    std::ofstream(dir / name, std::ios::binary) << bytes;
    return (dir / name).string();
  }
};

}  // namespace

TEST_CASE("read_file: every byte, any size, in one buffer", "[io]") {
  TempFolder t;
  const std::string odd("a\0b\r\nc\rd\n\xff", 10);
  CHECK(read_file(t.write("odd.bin", odd)) == odd);
  CHECK(read_file(t.write("empty.bin", "")).empty());
  std::string big(3 << 20, '\0');  // larger than a huge page and than the old 64 KB chunks
  for (size_t i = 0; i < big.size(); ++i) big[i] = static_cast<char>(i * 7919 % 251);
  CHECK(read_file(t.write("big.bin", big)) == big);
}

TEST_CASE("read_file: a pipe, which has no size, is read to its end", "[io]") {
  int fds[2];
  REQUIRE(::pipe(fds) == 0);
  const std::string text(10000, 'p');  // fits in the pipe's buffer: no writer thread needed
  REQUIRE(::write(fds[1], text.data(), text.size()) == static_cast<ssize_t>(text.size()));
  ::close(fds[1]);
  CHECK(read_file("/proc/self/fd/" + std::to_string(fds[0])) == text);
  ::close(fds[0]);
}

TEST_CASE("read_file: the memory limit, a missing file, a folder", "[io]") {
  TempFolder t;
  const std::string path = t.write("k.bin", std::string(1000, 'k'));
  CHECK(read_file(path, 1000).size() == 1000);
  CHECK_THROWS_WITH(read_file(path, 999), path + ": cannot read: its 1000 bytes exceed the memory limit of 999 bytes");
  // A pipe's bytes are counted as they come.
  int fds[2];
  REQUIRE(::pipe(fds) == 0);
  REQUIRE(::write(fds[1], "0123456789", 10) == 10);
  ::close(fds[1]);
  const std::string pipe = "/proc/self/fd/" + std::to_string(fds[0]);
  CHECK_THROWS_WITH(read_file(pipe, 9), pipe + ": cannot read: its 10 bytes exceed the memory limit of 9 bytes");
  ::close(fds[0]);
  CHECK_THROWS_WITH(read_file((t.dir / "none").string()),
                    Catch::StartsWith((t.dir / "none").string() + ": cannot read: No such file"));
  CHECK_THROWS_WITH(read_file(t.dir.string()), t.dir.string() + ": cannot read: it is a folder");
}
