#pragma once
// Writing output files so that a failure never leaves a partial file behind.
#include <string>
#include <string_view>

namespace mostyle {

// Writes `content` to a temporary file in the same folder as `path`, flushes it and renames it
// over `path`. Throws InputError ("PATH: cannot write: reason") and removes the temporary file
// on any failure.
void write_file_atomically(const std::string& path, std::string_view content);

// Reads a whole file as bytes. Throws InputError ("PATH: cannot read: reason").
std::string read_file(const std::string& path);

}  // namespace mostyle
