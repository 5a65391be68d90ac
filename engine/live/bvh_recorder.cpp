#include "engine/live/bvh_recorder.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>

#include "engine/io/bvh/bvh_write.h"
#include "engine/base/error.h"

namespace mostyle {
namespace {

constexpr int kCountDigits = 9;  // "Frames: 000000042": up to kMaxFrames

// Nine digits with leading zeros: every reader of a frame count reads them as the number.
void format_count(long long frames, char* out) {
  for (int i = kCountDigits - 1; i >= 0; --i) {
    out[i] = static_cast<char>('0' + frames % 10);
    frames /= 10;
  }
}

constexpr int kShortDigits = 7;  // a long line's values: within 5e-7 of each, relative

// Shortest text that reads back as the same double (digits 0), or `digits` significant ones.
void append_number(std::string* out, double v, int digits = 0) {
  char buffer[64];
  const auto r = digits > 0 ? std::to_chars(buffer, buffer + sizeof buffer, v, std::chars_format::general, digits)
                            : std::to_chars(buffer, buffer + sizeof buffer, v);
  out->append(buffer, r.ptr);
}

std::string temporary_name(const std::string& path) {
  static std::atomic<unsigned> counter{0};
  return path + ".tmp" + std::to_string(::getpid()) + "_" + std::to_string(counter++);
}

}  // namespace

BvhRecorder::BvhRecorder(const std::string& path, const Skeleton& skeleton, double frame_time)
    : path_(path), temporary_(temporary_name(path)), channels_(skeleton.channel_count) {
  const long page = ::sysconf(_SC_PAGESIZE);
  if (page > 0) page_ = static_cast<size_t>(page);
  fd_ = ::open(temporary_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd_ < 0) throw InputError(path_ + ": cannot write: " + std::strerror(errno));
  std::string header = format_bvh_hierarchy(skeleton);
  header += "MOTION\nFrames: ";
  // The count's digits within one page, so that rewriting them is one page's copy (whole or
  // not at all when a kill comes): spaces before them move them there when needed.
  if (header.size() / page_ != (header.size() + kCountDigits - 1) / page_) header.append(page_ - header.size() % page_, ' ');
  count_offset_ = header.size();
  header.append(kCountDigits, '0');
  // Each frame starts with its line end, so that the file's last line can take spaces.
  header += "\nFrame Time: ";
  append_number(&header, frame_time);
  try {
    write_all(header.data(), header.size());
  } catch (...) {
    ::close(fd_);
    ::unlink(temporary_.c_str());
    throw;
  }
}

BvhRecorder::~BvhRecorder() {
  if (frames_ > 0) {
    const ssize_t n = ::pwrite(fd_, "\n", 1, static_cast<off_t>(size_));
    (void)n;  // without it the file reads the same
  }
  ::close(fd_);
  if (frames_ == 0) ::unlink(temporary_.c_str());
}

void BvhRecorder::fail(int error) { throw InputError(path_ + ": cannot write: " + std::strerror(error)); }

void BvhRecorder::write_all(const char* data, size_t size) {
  while (size > 0) {
    const ssize_t n = ::pwrite(fd_, data, size, static_cast<off_t>(size_));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail(n < 0 ? errno : EIO);
    data += n;
    size -= static_cast<size_t>(n);
    size_ += static_cast<size_t>(n);
  }
}

void BvhRecorder::append(const double* values) {
  if (frames_ >= kMaxFrames)
    throw InputError(path_ + ": cannot write: the recording holds the most frames a BVH file may (" +
                     std::to_string(kMaxFrames) + ")");
  // Exact when the line fits in a page, else shorter, so that it may (see the header).
  for (int digits : {0, kShortDigits}) {
    line_.clear();
    for (int c = 0; c < channels_; ++c) {
      line_ += c ? ' ' : '\n';
      append_number(&line_, values[c], digits);
    }
    if (line_.size() <= page_) break;
  }
  if (channels_ == 0) line_ = "\n";
  const size_t before = size_;
  try {
    // Within one page (see the header), from the second frame on (the first is written before
    // the file appears): spaces end the line before when this one would cross into the next.
    const size_t room = page_ - size_ % page_;
    if (frames_ > 0 && line_.size() <= page_ && line_.size() > room) {
      const std::string pad(room, ' ');
      write_all(pad.data(), pad.size());
    }
    write_all(line_.data(), line_.size());
    char digits[kCountDigits];
    format_count(frames_ + 1, digits);
    for (;;) {
      const ssize_t n = ::pwrite(fd_, digits, kCountDigits, static_cast<off_t>(count_offset_));
      if (n == kCountDigits) break;
      if (n < 0 && errno == EINTR) continue;
      fail(n < 0 ? errno : EIO);
    }
  } catch (...) {
    // Back to the last whole frame: a failed write may have added part of a line. Should this
    // fail too, the reader still loads the frames before the cut line.
    size_ = before;
    const int truncated = ::ftruncate(fd_, static_cast<off_t>(size_));
    (void)truncated;
    throw;
  }
  ++frames_;
  if (frames_ == 1 && std::rename(temporary_.c_str(), path_.c_str()) != 0) {
    const int e = errno;
    frames_ = 0;
    throw InputError(path_ + ": cannot write: " + std::strerror(e));
  }
}

std::string append_or_stop(std::unique_ptr<BvhRecorder>* recorder, const double* values) {
  if (!*recorder) return std::string();
  try {
    (*recorder)->append(values);
  } catch (const InputError& e) {
    const std::string why = std::string(e.what()) + "; the recording stops at " +
                            std::to_string((*recorder)->frames()) + " frames";
    recorder->reset();
    return why;
  }
  return std::string();
}

}  // namespace mostyle
