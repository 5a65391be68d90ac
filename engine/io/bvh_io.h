#pragma once
// Reading and writing BVH files. Reads every convention seen in real data: any depth (no
// recursion), 0..6 channels per joint in any order, position channels on any joint (they
// replace the OFFSET, DESIGN.md 1), End Sites, LF/CRLF/CR line endings, tabs, scientific
// notation, names with spaces. Numbers are parsed locale-independently with std::from_chars.
#include <string>
#include <string_view>
#include <vector>

#include "engine/io/clip.h"

namespace mostyle {

// Parses BVH text. `source` names the file in messages. Recoverable defects (declared and
// actual frame counts differ, a cut last frame line) load the complete frames and append one
// sentence each, "SOURCE:LINE: ...", to *warnings. Throws InputError
// "SOURCE:LINE: expected X, found Y" on anything else: a non-BVH or cut header, braces,
// channels, a short OFFSET, a frame count below 0 or above 1e8, a frame line with extra values,
// a value that is not a finite number (naming frame and channel), a nameless joint.
// O(size) time; memory O(size), never allocated from the declared frame count alone.
Clip parse_bvh(std::string_view text, const std::string& source,
               std::vector<std::string>* warnings = nullptr);

// Reads and parses a file; throws InputError naming the file when it cannot be read.
Clip read_bvh_file(const std::string& path, std::vector<std::string>* warnings = nullptr);

// Standard BVH text (LF, tab indent, numbers in shortest round-trip form, so values read back
// bit-exact). A root with position channels is written with OFFSET 0 0 0: its channels place it
// (Blender's reading and ours), and three.js, which adds the OFFSET, then reads it the same.
// Joints below the root keep their OFFSET; three.js adds it to their position channels where
// Blender replaces it, so files with such joints (Bandai) read differently in three.js whatever
// the writer does, short of zeroing their OFFSETs and losing the rest skeleton.
std::string format_bvh(const Clip& clip);

// Writes format_bvh(clip) to a temporary file beside `path` and renames it over `path`.
// Throws InputError when the file cannot be written; never leaves a partial file.
void write_bvh_file(const Clip& clip, const std::string& path);

}  // namespace mostyle
