#pragma once
// Writing BVH files (bvh_read.h reads them): the text a clip is, and the file written atomically.
#include <string>

#include "engine/base/clip.h"

namespace mostyle {

// Standard BVH text (LF, tab indent, numbers in shortest round-trip form, so values read back
// bit-exact). A root with position channels is written with OFFSET 0 0 0: its channels place it
// (Blender's reading and ours), and three.js, which adds the OFFSET, then reads it the same.
// Joints below the root keep their OFFSET; three.js adds it to their position channels where
// Blender replaces it, so files with such joints (Bandai) read differently in three.js whatever
// the writer does, short of zeroing their OFFSETs and losing the rest skeleton.
std::string format_bvh(const Clip& clip);

// format_bvh's first part: "HIERARCHY" and the joints, up to and without "MOTION".
std::string format_bvh_hierarchy(const Skeleton& skeleton);

// Writes format_bvh(clip) to a temporary file beside `path` and renames it over `path`.
// Throws InputError when the file cannot be written; never leaves a partial file.
void write_bvh_file(const Clip& clip, const std::string& path);

}  // namespace mostyle
