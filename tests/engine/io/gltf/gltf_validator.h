#pragma once
// Runs the Khronos glTF validator (tests/tools/validate_gltf.js, npm package gltf-validator) on
// a file, for tests; says when node or the package is missing so the test can skip.
#include <sys/wait.h>

#include <cstdlib>
#include <string>

namespace mostyle::test {

enum class Validation { kClean, kIssues, kUnavailable };

// kClean: 0 errors and 0 warnings; kIssues: some (printed by the script); kUnavailable: no
// node, or no gltf-validator package.
inline Validation validate_gltf(const std::string& file) {
  if (std::system("node --version >/dev/null 2>&1") != 0) return Validation::kUnavailable;
  const std::string script = std::string(MOSTYLE_ASSETS_DIR) + "/../tests/tools/validate_gltf.js";
  const int raw = std::system(("node \"" + script + "\" \"" + file + "\"").c_str());
  const int status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  if (status == 0) return Validation::kClean;
  if (status == 2) return Validation::kUnavailable;
  return Validation::kIssues;
}

}  // namespace mostyle::test

// Checks a file with the validator, or says visibly that it could not.
#define MOSTYLE_CHECK_GLTF_VALID(file)                                                              \
  do {                                                                                              \
    const auto validation_ = mostyle::test::validate_gltf(file);                                    \
    if (validation_ == mostyle::test::Validation::kUnavailable)                                     \
      WARN("skipped the Khronos validator: node or the npm package gltf-validator is missing "       \
           "(app/install-deps.sh installs them)");                                                   \
    else                                                                                            \
      CHECK(validation_ == mostyle::test::Validation::kClean);                                      \
  } while (0)
