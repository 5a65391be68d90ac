// Every input a fuzz target once crashed on (tests/fuzz/regressions/<target>/), and every seed
// (tests/fuzz/seeds/<target>/), fed to its reader in the normal test build: each loads or is
// refused with an InputError, and passes the checks of fuzz_readers.cpp.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/fuzz/fuzz_readers.h"

namespace fs = std::filesystem;

TEST_CASE("fuzz regressions and seeds load or are refused cleanly", "[fuzz]") {
  int inputs = 0;
  for (const char* kind : {"regressions", "seeds"}) {
    for (const std::string& target : mostyle::fuzz::target_names()) {
      const fs::path dir = fs::path(MOSTYLE_FUZZ_DIR) / kind / target;
      if (!fs::is_directory(dir)) continue;
      for (const auto& entry : fs::directory_iterator(dir)) {
        if (!entry.is_regular_file()) continue;
        std::ifstream in(entry.path(), std::ios::binary);
        std::stringstream bytes;
        bytes << in.rdbuf();
        INFO(entry.path().string());
        CHECK_NOTHROW(mostyle::fuzz::read_as(target, bytes.str()));
        ++inputs;
      }
    }
  }
  CHECK(inputs > 0);
}
