#include "engine/prepare/major_take.h"

#include <algorithm>
#include <cmath>

#include "engine/base/error.h"
#include "engine/kinematics/kinematics.h"
#include "engine/kinematics/resample.h"

namespace mostyle {

MajorTake extract_major_take(const Clip& clip, const MajorMapping& mapping,
                             const std::vector<int>& majors, double fps) {
  if (clip.frames() == 0) throw InputError(clip.source + ": has no frames to blend");
  MajorTake take;
  take.source = clip.source;
  take.majors = majors;
  take.parents = subset_parents(majors);
  for (int major : majors) {
    const int joint = mapping.joint[major];
    take.clip_joints.push_back(joint);
    take.names.push_back(clip.skeleton.joints[joint].name);
  }
  const bool same_rate = fps <= 0 || std::abs(fps - clip.fps()) < 1e-9;
  // Fingers and other joints off the major joints' chains are not resampled: nothing reads them.
  const Clip resampled = same_rate ? Clip() : resample_clip(clip, fps, take.clip_joints);
  const Clip& source = same_rate ? clip : resampled;
  take.fps = same_rate ? clip.fps() : fps;
  take.world = joint_positions(source, take.clip_joints);  // FK of the major joints' chains only
  return take;
}

int major_column(const std::vector<int>& majors, int major) {
  auto it = std::find(majors.begin(), majors.end(), major);
  return it == majors.end() ? -1 : static_cast<int>(it - majors.begin());
}

}  // namespace mostyle
