#include "engine/base/memory_limit.h"

#include <catch2/catch.hpp>
#include <cstring>
#include <string>
#include <vector>

#include "engine/base/huge_pages.h"

using namespace mostyle;

TEST_CASE("describe_bytes: bytes, then KB .. GB in tenths rounded up", "[io]") {
  CHECK(describe_bytes(0) == "0 bytes");
  CHECK(describe_bytes(1) == "1 byte");
  CHECK(describe_bytes(1023) == "1023 bytes");
  CHECK(describe_bytes(1024) == "1 KB");
  CHECK(describe_bytes(1536) == "1.5 KB");
  CHECK(describe_bytes(1025) == "1.1 KB");  // up: over a limit never reads as under it
  CHECK(describe_bytes(size_t{810} << 10) == "810 KB");
  CHECK(describe_bytes(8080128) == "7.8 MB");
  CHECK(describe_bytes(kDefaultMaxBytes) == "4 GB");
  CHECK(describe_bytes(kDefaultMaxBytes + 1) == "4.1 GB");
  CHECK(describe_bytes(SIZE_MAX) == "16 EB");
}

TEST_CASE("advise_huge_pages is a hint: contents kept, any pointer and size accepted", "[io]") {
  advise_huge_pages(nullptr, 0);
  advise_huge_pages(nullptr, size_t{64} << 20);
  std::vector<char> small(100, 'x');
  advise_huge_pages(small.data(), small.size());
  // Unaligned, larger than a huge page, partly written before the hint.
  std::vector<char> big((size_t{5} << 20) + 123, 'a');
  advise_huge_pages(big.data() + 7, big.size() - 7);
  for (size_t i = 0; i < big.size(); i += 4096) CHECK(big[i] == 'a');
  std::memset(big.data(), 'b', big.size());
  CHECK(big.back() == 'b');
}

TEST_CASE("parse_memory_limit: whole megabytes from 1 up, the default when empty", "[io]") {
  CHECK(parse_memory_limit("") == kDefaultMaxBytes);
  CHECK(parse_memory_limit("1") == size_t{1} << 20);
  CHECK(parse_memory_limit("4096") == kDefaultMaxBytes);
  for (const char* bad : {"0", "-1", "1.5", "lots", " 1", "1 ", "99999999999999999999"}) {
    INFO(bad);
    CHECK_THROWS_WITH(parse_memory_limit(bad), std::string("MOSTYLE_MAX_MEMORY_MB: expected a whole number of "
                                                           "megabytes from 1 up, found '") + bad + "'");
  }
}
