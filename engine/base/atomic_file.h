#pragma once
// Writing output files so that a failure never leaves a partial file behind.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace mostyle {

// Writes `content` to a temporary file in the same folder as `path`, flushes it and renames it
// over `path`. Throws InputError ("PATH: cannot write: reason") and removes the temporary file
// on any failure.
void write_file_atomically(const std::string& path, std::string_view content);

// Reads a whole file as bytes, in one pass into one buffer of the file's size (a pipe or a file
// that grows meanwhile is read on in chunks). Throws InputError ("PATH: cannot read: reason"),
// also when the file holds more than max_bytes, before reading it. O(size) time and memory.
std::string read_file(const std::string& path, size_t max_bytes = SIZE_MAX);

}  // namespace mostyle
