#pragma once
// One take reduced to the major skeleton: world positions of the canonical joints two takes
// share, at the working frame rate.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "engine/base/clip.h"
#include "engine/prepare/major_skeleton.h"

namespace mostyle {

struct MajorTake {
  std::string source;
  std::vector<int> majors;          // canonical joint of each column triple (canonical order)
  std::vector<int> parents;         // parent within `majors`, -1 for the hips
  std::vector<int> clip_joints;     // the clip's joint index of each
  std::vector<std::string> names;   // the clip's joint names
  Eigen::MatrixXd world;            // F x 3M positions, file units, Y up
  double fps = 30.0;                // frames per second of `world`
};

// Resamples the clip to `fps` (0 keeps its own rate), runs FK and keeps the `majors` joints
// (a subset from shared_major_joints). Throws InputError when the clip has no frames.
MajorTake extract_major_take(const Clip& clip, const MajorMapping& mapping,
                             const std::vector<int>& majors, double fps);

// Column of canonical joint `major` within a take's majors, or -1.
int major_column(const std::vector<int>& majors, int major);

}  // namespace mostyle
