#pragma once
// What `mostyle-cli info` says of one take of a file, as values and as the JSON `info --json`
// prints: for the command and the Python module's info().
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/cli/synthesis_request.h"
#include "engine/align/cycles.h"
#include "engine/base/clip.h"
#include "engine/io/scene_animation.h"
#include "engine/kinematics/units.h"
#include "engine/prepare/major_skeleton.h"

namespace mostyle::cli {

// Where a file's one skeleton comes from, in words and as a JSON key.
struct SkeletonOrigin {
  const char* key = "";
  const char* words = "";
};

// What `info` prints of one take of a file.
struct FileInfo {
  std::shared_ptr<const Clip> clip;
  MajorMapping majors;
  std::optional<TakeCycles> cycles;  // in its own frames; none when it has no major joints
  std::string no_cycles;             // why there are none
  std::vector<TakeInfo> takes;       // every take of the file
  SkeletonOrigin origin;
  UnitsGuess units;
};

// Reads the take (path or FILE#ANIMATION; `take` and `fps` as --take and --fps, "" and 0 for
// the defaults; `mapping` a mapping file or ""), its major joints, cycles and the file's takes.
// The reader's warnings go to stderr. Throws InputError on an unreadable file or mapping.
FileInfo read_file_info(const std::string& path, const std::string& take, double fps, const std::string& mapping);

// What `info --json` prints; `path` as given.
Json info_json(const std::string& path, const FileInfo& info);

// A joint's rotation channels' axes in file order ("ZXY"; "" without rotation channels).
std::string joint_rotation_order(const Joint& joint);

}  // namespace mostyle::cli
