#include "engine/kinematics/kinematics.h"

#include <cassert>

#include "engine/kinematics/euler.h"

namespace mostyle {

Eigen::Matrix3d joint_local_rotation(const Joint& joint, const double* frame_values) {
  Eigen::Matrix3d r = Eigen::Matrix3d::Identity();
  for (size_t c = 0; c < joint.channels.size(); ++c) {
    const Channel ch = joint.channels[c];
    if (is_rotation(ch)) r = r * axis_rotation(channel_axis(ch), frame_values[joint.first_channel + c]);
  }
  return r;
}

Eigen::Vector3d joint_local_translation(const Joint& joint, const double* frame_values) {
  // DESIGN.md 1, as Blender's importer does it (io_anim_bvh: a bone with location channels is
  // placed at (lx, ly, lz) relative to its parent, unset ones 0.0, whatever its OFFSET says).
  bool has_position = false;
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  for (size_t c = 0; c < joint.channels.size(); ++c) {
    const Channel ch = joint.channels[c];
    if (is_position(ch)) {
      t[channel_axis(ch)] = frame_values[joint.first_channel + c];
      has_position = true;
    }
  }
  return has_position ? t : joint.offset;
}

namespace {

// Fills global rotations and positions of one frame; joints are stored parents first.
void frame_pose(const Skeleton& s, const double* values, std::vector<Eigen::Matrix3d>* rotations,
                std::vector<Eigen::Vector3d>* positions) {
  const size_t n = s.joints.size();
  rotations->resize(n);
  positions->resize(n);
  for (size_t i = 0; i < n; ++i) {
    const Joint& j = s.joints[i];
    assert(j.parent < static_cast<int>(i) && "joints must come after their parent");
    const Eigen::Matrix3d local_r = joint_local_rotation(j, values);
    const Eigen::Vector3d local_t = joint_local_translation(j, values);
    if (j.parent < 0) {
      (*rotations)[i] = local_r;
      (*positions)[i] = local_t;
    } else {
      (*rotations)[i] = (*rotations)[j.parent] * local_r;
      (*positions)[i] = (*positions)[j.parent] + (*rotations)[j.parent] * local_t;
    }
  }
}

}  // namespace

Eigen::MatrixXd joint_positions(const Clip& clip) {
  const Skeleton& s = clip.skeleton;
  const int n = static_cast<int>(s.joints.size());
  Eigen::MatrixXd out(clip.frames(), 3 * n);
  std::vector<Eigen::Matrix3d> rotations;
  std::vector<Eigen::Vector3d> positions;
  for (int f = 0; f < clip.frames(); ++f) {
    frame_pose(s, clip.motion.row(f).data(), &rotations, &positions);
    for (int i = 0; i < n; ++i) out.block<1, 3>(f, 3 * i) = positions[i].transpose();
  }
  return out;
}

Pose pose_at(const Clip& clip, int frame) {
  assert(frame >= 0 && frame < clip.frames());
  Pose pose;
  frame_pose(clip.skeleton, clip.motion.row(frame).data(), &pose.rotations, &pose.positions);
  return pose;
}

std::vector<Eigen::Vector3d> rest_positions(const Skeleton& skeleton) {
  // The rest rotations, and the OFFSET where position channels would be (zero would collapse joints).
  std::vector<Eigen::Vector3d> out(skeleton.joints.size());
  std::vector<Eigen::Matrix3d> rotation(skeleton.joints.size());
  for (size_t i = 0; i < skeleton.joints.size(); ++i) {
    const Joint& j = skeleton.joints[i];
    if (j.parent < 0) {
      out[i] = j.offset;
      rotation[i] = j.rest_rotation;
    } else {
      out[i] = out[j.parent] + rotation[j.parent] * j.offset;
      rotation[i] = rotation[j.parent] * j.rest_rotation;
    }
  }
  return out;
}

}  // namespace mostyle
