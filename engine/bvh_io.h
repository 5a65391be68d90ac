#pragma once
// Reading and writing BVH files. Reads every convention seen in real data: any depth (no
// recursion), 0..6 channels per joint in any order, position channels on any joint (they
// replace the OFFSET, DESIGN.md 1), End Sites, LF/CRLF/CR line endings, tabs, scientific
// notation, names with spaces. Numbers are parsed locale-independently with std::from_chars.
#include <string>
#include <string_view>
#include <vector>

#include "engine/clip.h"

namespace mostyle {

// Parses BVH text. `source` names the file in messages. Recoverable defects (declared and
// actual frame counts differ, a cut last frame line) load the complete frames and append one
// sentence each to *warnings. Throws InputError "SOURCE:LINE: expected X, found Y" on anything
// else. O(size) time; memory O(size) at most, never allocated from an unchecked count.
Clip parse_bvh(std::string_view text, const std::string& source,
               std::vector<std::string>* warnings = nullptr);

// Reads and parses a file; throws InputError naming the file when it cannot be read.
Clip read_bvh_file(const std::string& path, std::vector<std::string>* warnings = nullptr);

// Standard BVH text (LF, tab indent, numbers in shortest round-trip form).
std::string format_bvh(const Clip& clip);

// Writes format_bvh(clip) to a temporary file beside `path` and renames it over `path`.
// Throws InputError when the file cannot be written; never leaves a partial file.
void write_bvh_file(const Clip& clip, const std::string& path);

}  // namespace mostyle
