#pragma once
// A BVH file written one frame at a time, as a stream comes, that reads as a whole BVH file at
// every moment: when the stream ends, when the writer is killed (SIGKILL included) and while it
// is being written.
//
// How: the file appears (by a rename) only with its header and first frame. Each later frame
// goes to the file as one write of "\n" and its values, within one page of the file (when it
// would cross into the next page, spaces at the end of the line before move it there), so a
// kill never leaves part of a frame: Linux stops a write to a file for a fatal signal only
// between pages. Then the header's "Frames:" count, nine digits with leading zeros within one
// page, is rewritten in place. The count is never ahead of the lines: a reader that trusts it
// (three.js) reads whole frames, one that reads every line after "Frame Time" (Blender) reads
// them all, and ours loads them all (with a warning when the count is one behind). The last
// line ends with a line end once the recorder closes. Values are written exactly (the shortest
// text that reads back as the same double) when the frame's line fits in a page, else with 7
// significant digits (within 5e-7 of each value, relative; a 59-joint Axis skeleton with six
// channels a joint takes about 3.5 KB). A line longer than a page even so (over about 300
// channels) spans pages and may be cut by a kill: ours then loads the frames before it, with a
// warning. Nothing is synced to disk: what a power cut keeps is the file system's.
#include <cstddef>
#include <memory>
#include <string>

#include "engine/base/clip.h"

namespace mostyle {

class BvhRecorder {
 public:
  // The most frames a recording holds: our reader's limit on a BVH file's frame count.
  static constexpr long long kMaxFrames = 100'000'000;

  // Prepares a recording of `skeleton` at `frame_time` seconds per frame to `path`: writes its
  // header to a temporary file beside `path`, which becomes `path` at the first frame (until
  // then `path` is as it was). Throws InputError "PATH: cannot write: reason" when the folder
  // cannot hold it.
  BvhRecorder(const std::string& path, const Skeleton& skeleton, double frame_time);
  // Ends the last line and closes the file; a recording that got no frame leaves no file (its
  // temporary one removed).
  ~BvhRecorder();
  BvhRecorder(const BvhRecorder&) = delete;
  BvhRecorder& operator=(const BvhRecorder&) = delete;

  // Appends one frame: skeleton.channel_count values (degrees, file units, the skeleton's
  // channel order), written as the header says (exactly when the line fits in a page). Two
  // system calls (the line, the count; three when it pads) and, for the first frame, the rename. Throws InputError
  // "PATH: cannot write: reason" when a write fails (a full disk) or when the recording already
  // holds kMaxFrames frames; the file then stays as it was before this frame.
  void append(const double* values);

  long long frames() const { return frames_; }
  const std::string& path() const { return path_; }

 private:
  void write_all(const char* data, size_t size);
  [[noreturn]] void fail(int error);

  std::string path_, temporary_;
  int fd_ = -1;
  int channels_ = 0;
  long long frames_ = 0;
  size_t size_ = 0;          // bytes in the file
  size_t count_offset_ = 0;  // where the nine digits of "Frames:" are
  size_t page_ = 4096;
  std::string line_;         // the frame line being written, reused
};

// Appends one frame to *recorder when it holds one. A write that fails ends the recording
// (*recorder closed and null, its file whole up to the frame before) and returns why in one
// sentence: "PATH: cannot write: No space left on device; the recording stops at 1200 frames";
// "" otherwise.
std::string append_or_stop(std::unique_ptr<BvhRecorder>* recorder, const double* values);

}  // namespace mostyle
