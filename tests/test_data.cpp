#include "tests/test_data.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>

namespace mostyle::test {
namespace fs = std::filesystem;

namespace {
std::vector<std::string> bvh_files_in(const fs::path& dir) {
  std::vector<std::string> out;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return out;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    if (entry.path().extension() == ".bvh") out.push_back(entry.path().string());
  }
  std::sort(out.begin(), out.end());
  return out;
}
// ../shared/motions, or the folder MOSTYLE_SHARED_MOTIONS_DIR names when set (CI sets it to a
// folder that does not exist, to run the tests as a clone with nothing beside it does).
std::string shared_folder() {
  const char* dir = std::getenv("MOSTYLE_SHARED_MOTIONS_DIR");
  return dir != nullptr ? std::string(dir) : std::string(MOSTYLE_SHARED_MOTIONS);
}

}  // namespace

std::string shared_motion(const std::string& name) {
  fs::path p = fs::path(shared_folder()) / name;
  std::error_code ec;
  return fs::exists(p, ec) ? p.string() : std::string();
}

std::vector<std::string> shared_motions() { return bvh_files_in(shared_folder()); }

std::string asset(const std::string& name) { return (fs::path(MOSTYLE_ASSETS_DIR) / name).string(); }

std::vector<std::string> asset_motions() {
  return bvh_files_in(fs::path(MOSTYLE_ASSETS_DIR) / "motions");
}

}  // namespace mostyle::test
