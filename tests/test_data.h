#pragma once
// Where tests find real motion data: ../shared/motions (not in a user's clone) and assets/.
#include <string>
#include <vector>

namespace mostyle::test {

// Full path of a file in ../shared/motions, or "" when that folder is absent.
std::string shared_motion(const std::string& name);
// Every .bvh in ../shared/motions, sorted; empty when the folder is absent.
std::vector<std::string> shared_motions();
// Full path of a file in assets/ (always present).
std::string asset(const std::string& name);
// Every .bvh in assets/motions, sorted.
std::vector<std::string> asset_motions();

}  // namespace mostyle::test

// Skips the rest of a test case, visibly, when ../shared/motions is absent.
#define MOSTYLE_REQUIRE_SHARED_MOTIONS()                                         \
  do {                                                                            \
    if (mostyle::test::shared_motions().empty()) {                               \
      WARN("skipped: ../shared/motions is absent (tests use assets/ instead)"); \
      return;                                                                     \
    }                                                                             \
  } while (0)
