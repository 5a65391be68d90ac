#pragma once
// How much memory a reader of outside input may take, and how messages show amounts of it.
#include <cstddef>
#include <string>

namespace mostyle {

// The default bound on what one file may make a reader allocate: 4 GB (1 GB = 2^30 bytes).
constexpr size_t kDefaultMaxBytes = size_t{4} << 30;

// "812 bytes", "1.5 KB", "7.7 MB", "4 GB": tenths rounded up, ".0" dropped; 1 KB = 1024 bytes.
std::string describe_bytes(size_t bytes);

}  // namespace mostyle
