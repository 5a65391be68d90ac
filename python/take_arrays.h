#pragma once
// A take as the Python module's arrays hold it (joint names, parents, offsets, local rotations as
// quaternions, the root's path, a frame rate) and back: a Take built from arrays becomes a Clip
// and goes through the same preparation as a take read from a file.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "engine/base/clip.h"

namespace mostyle {

struct TakeArrays {
  std::vector<std::string> joint_names;  // J, End Sites named "<parent's name> End Site"
  std::vector<int> parents;              // J, -1 for the root (joint 0), else an earlier joint
  Eigen::MatrixXd offsets;               // J x 3: each joint's translation in its parent, file units
  Eigen::MatrixXd rotations;             // F x 4J: each joint's local rotation, w x y z per joint
  Eigen::MatrixXd root_positions;        // F x 3: the root's translation, file units
  // F x 3J: each joint's translation in its parent per frame, or empty: every joint below the
  // root at its offset. Rigs whose hips move below a still root (Bandai's) need it.
  Eigen::MatrixXd translations;
  double fps = 30.0;
};

// The clip the arrays describe: the root with position and rotation channels (root_positions
// wins over translations' first joint), every other joint rotation channels, and position
// channels too where its translations leave its offset, (ZXY, the angles unwrapped frame to frame), an End Site (a leaf named after
// its parent, as the BVH reader names them) none. `source` names the clip in messages. Throws
// InputError on a shape that does not match, a parent that does not come before its child, a
// value that is not finite, a zero quaternion or a bad frame rate. O(F x J).
Clip clip_from_arrays(const TakeArrays& arrays, const std::string& source);

// The arrays of a clip: its joints in order (End Sites too), their OFFSETs, each joint's local
// translation (as FK reads it: position channels replace the OFFSET) and rotation per frame (w >= 0 at the first frame, then on the side nearer the frame
// before, so curves do not flip), the first root's translation per frame. O(F x J).
TakeArrays arrays_from_clip(const Clip& clip);

}  // namespace mostyle
