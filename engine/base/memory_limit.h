#pragma once
// How much memory a reader of outside input may take, and how messages show amounts of it.
#include <cstddef>
#include <string>
#include <string_view>

namespace mostyle {

// The default bound on what one file may make a reader allocate: 4 GB (1 GB = 2^30 bytes).
constexpr size_t kDefaultMaxBytes = size_t{4} << 30;

// The limit the environment variable MOSTYLE_MAX_MEMORY_MB sets, from its value (the programs
// read the environment, this only parses it): empty gives kDefaultMaxBytes, else a whole number
// of megabytes (2^20 bytes) from 1 up. Throws InputError "MOSTYLE_MAX_MEMORY_MB: expected a whole
// number of megabytes from 1 up, found 'x'" (x cut at 40 characters).
constexpr const char* kMemoryLimitVariable = "MOSTYLE_MAX_MEMORY_MB";
size_t parse_memory_limit(std::string_view megabytes);

// "812 bytes", "1.5 KB", "7.7 MB", "4 GB": tenths rounded up, ".0" dropped; 1 KB = 1024 bytes.
std::string describe_bytes(size_t bytes);

}  // namespace mostyle
