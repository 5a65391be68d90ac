#include "engine/base/atomic_file.h"

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <sys/stat.h>
#include <unistd.h>

#include "engine/base/error.h"
#include "engine/base/huge_pages.h"
#include "engine/base/memory_limit.h"

namespace mostyle {
namespace {

std::string temporary_name(const std::string& path) {
  static std::atomic<unsigned> counter{0};
  return path + ".tmp" + std::to_string(::getpid()) + "_" + std::to_string(counter++);
}

}  // namespace

void write_file_atomically(const std::string& path, std::string_view content) {
  const std::string tmp = temporary_name(path);
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) throw InputError(path + ": cannot write: " + std::strerror(errno));
  errno = 0;
  bool ok = std::fwrite(content.data(), 1, content.size(), f) == content.size();
  ok = (std::fflush(f) == 0) && ok;
  // On disk before the rename, so a crash leaves the old file or the new one, never an empty one.
  ok = ok && ::fsync(::fileno(f)) == 0;
  const int saved_errno = errno;
  ok = (std::fclose(f) == 0) && ok;
  if (!ok) {
    std::remove(tmp.c_str());
    throw InputError(path + ": cannot write: " + std::strerror(saved_errno ? saved_errno : EIO));
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const int e = errno;
    std::remove(tmp.c_str());
    throw InputError(path + ": cannot write: " + std::strerror(e));
  }
}

std::string read_file(const std::string& path, size_t max_bytes) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw InputError(path + ": cannot read: it is a folder");
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!f) throw InputError(path + ": cannot read: " + std::strerror(errno));
  auto too_big = [&](size_t bytes) {
    return InputError(path + ": cannot read: its " + describe_bytes(bytes) +
                      " exceed the memory limit of " + describe_bytes(max_bytes));
  };
  // One buffer of the file's size, filled by one read: growing a string chunk by chunk copies
  // the text over and faults in more pages than it holds, which dominates reading a large take.
  // Bench: BM_ReadPair22MB (tests/bench/bvh_bench.cpp).
  struct stat st {};
  size_t size = 0;
  if (::fstat(::fileno(f.get()), &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0)
    size = static_cast<size_t>(st.st_size);
  if (size > max_bytes) throw too_big(size);
  std::string out;
  out.reserve(size);
  advise_huge_pages(out.data(), size);
  out.resize(size);
  const size_t n = std::fread(out.data(), 1, size, f.get());
  out.resize(n);
  if (n == size) {
    // The rest, if any: a pipe, or a file that grew since fstat.
    char buffer[1 << 16];
    size_t chunk;
    while ((chunk = std::fread(buffer, 1, sizeof buffer, f.get())) > 0) {
      if (chunk > max_bytes - out.size()) throw too_big(out.size() + chunk);
      out.append(buffer, chunk);
    }
  }
  if (std::ferror(f.get()) != 0) throw InputError(path + ": cannot read: I/O error");
  return out;
}

}  // namespace mostyle
