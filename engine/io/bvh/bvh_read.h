#pragma once
// Reading BVH files (bvh_write.h writes them). Reads every convention seen in real data: any
// depth (no recursion), 0..6 channels per joint in any order, position channels on any joint (they
// replace the OFFSET, as Blender reads them), End Sites, LF/CRLF/CR line endings, tabs, scientific
// notation, names with spaces. Numbers are parsed locale-independently: plain decimals by an
// exact fast path, the rest with std::from_chars; both give the correctly rounded double.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "engine/base/clip.h"
#include "engine/base/memory_limit.h"

namespace mostyle {

struct BvhReadOptions {
  // The most memory the frames may take (frames x channels x 8 bytes). A file that needs more is
  // refused at its Frames: line, before the frames are allocated; read_bvh_file also refuses a
  // file larger than this before reading it. The CLI takes it from MOSTYLE_MAX_MEMORY_MB.
  size_t max_bytes = kDefaultMaxBytes;
};

// Parses BVH text. `source` names the file in messages. Recoverable defects (declared and
// actual frame counts differ, a cut last frame line) load the complete frames and append one
// sentence each, "SOURCE:LINE: ...", to *warnings. Throws InputError
// "SOURCE:LINE: expected X, found Y" on anything else: a non-BVH or cut header, braces,
// channels, a short OFFSET, a frame count below 0 or above 1e8, frames over options.max_bytes,
// a frame line with extra values, a value that is not a finite number (naming frame and
// channel), a nameless joint or one whose name ends in '{' (no BVH text could hold it).
// O(size) time, in place (no copy of the text). Memory: the frames, reserved from the declared
// count but never more than the text can hold (each value takes at least 2 bytes).
Clip parse_bvh(std::string_view text, const std::string& source,
               std::vector<std::string>* warnings = nullptr, const BvhReadOptions& options = {});

// Reads a file into one buffer and parses it; throws InputError naming the file when it cannot
// be read. About 1 ms per MB of CMU take, reading included (tests/bench/bvh_bench).
Clip read_bvh_file(const std::string& path, std::vector<std::string>* warnings = nullptr,
                   const BvhReadOptions& options = {});

}  // namespace mostyle
