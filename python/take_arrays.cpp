#include "python/take_arrays.h"

#include <Eigen/Geometry>
#include <cmath>

#include "engine/base/error.h"
#include "engine/kinematics/euler.h"
#include "engine/kinematics/kinematics.h"

namespace mostyle {
namespace {

std::string shape_text(Eigen::Index rows, Eigen::Index cols) {
  return std::to_string(rows) + " x " + std::to_string(cols);
}

void check_finite(const Eigen::MatrixXd& m, const std::string& name, const std::string& source) {
  if (!m.allFinite()) throw InputError(source + ": " + name + " holds a value that is not finite");
}

void check_arrays(const TakeArrays& a, const std::string& source) {
  const Eigen::Index joints = static_cast<Eigen::Index>(a.joint_names.size());
  if (joints == 0) throw InputError(source + ": a take needs at least one joint (joint_names is empty)");
  if (static_cast<Eigen::Index>(a.parents.size()) != joints)
    throw InputError(source + ": expected one parent per joint (" + std::to_string(joints) + "), found " +
                     std::to_string(a.parents.size()));
  if (a.offsets.rows() != joints || a.offsets.cols() != 3)
    throw InputError(source + ": expected offsets of " + shape_text(joints, 3) + " (joints x 3), found " +
                     shape_text(a.offsets.rows(), a.offsets.cols()));
  const Eigen::Index frames = a.rotations.rows();
  if (frames == 0) throw InputError(source + ": a take needs at least one frame (rotations has none)");
  if (a.rotations.cols() != 4 * joints)
    throw InputError(source + ": expected rotations of frames x " + std::to_string(joints) +
                     " x 4 (w, x, y, z per joint), found " + std::to_string(a.rotations.cols() / 4) + " joints");
  if (a.root_positions.rows() != frames || a.root_positions.cols() != 3)
    throw InputError(source + ": expected root_positions of " + shape_text(frames, 3) +
                     " (one row per frame of rotations), found " +
                     shape_text(a.root_positions.rows(), a.root_positions.cols()));
  if (a.translations.size() > 0 && (a.translations.rows() != frames || a.translations.cols() != 3 * joints))
    throw InputError(source + ": expected translations of frames x " + std::to_string(joints) + " x 3 (" +
                     std::to_string(frames) + " frames, as rotations), found " +
                     shape_text(a.translations.rows(), a.translations.cols() / 3) + " x 3");
  if (!(a.fps > 0.0 && std::isfinite(a.fps)))
    throw InputError(source + ": expected a positive frame rate, found " + std::to_string(a.fps));
  if (a.parents[0] != -1)
    throw InputError(source + ": joint 0 ('" + a.joint_names[0] + "') must be the root (parent -1), found parent " +
                     std::to_string(a.parents[0]));
  // FK runs parents first, as the readers store joints.
  for (size_t j = 1; j < a.parents.size(); ++j)
    if (a.parents[j] < 0 || a.parents[j] >= static_cast<int>(j))
      throw InputError(source + ": joint " + std::to_string(j) + " ('" + a.joint_names[j] +
                       "') needs a parent that comes before it, found " + std::to_string(a.parents[j]));
  check_finite(a.offsets, "offsets", source);
  check_finite(a.rotations, "rotations", source);
  check_finite(a.root_positions, "root_positions", source);
  check_finite(a.translations, "translations", source);
}

// A joint below the root whose translation leaves its offset at some frame: it needs position
// channels to hold it.
bool translation_moves(const TakeArrays& a, size_t joint) {
  if (joint == 0 || a.translations.size() == 0) return false;
  const Eigen::Index c = 3 * static_cast<Eigen::Index>(joint);
  for (Eigen::Index f = 0; f < a.translations.rows(); ++f)
    if (a.translations.block<1, 3>(f, c) != a.offsets.row(static_cast<Eigen::Index>(joint))) return true;
  return false;
}

Skeleton skeleton_from_arrays(const TakeArrays& a) {
  const size_t n = a.joint_names.size();
  std::vector<bool> has_children(n, false);
  for (size_t j = 1; j < n; ++j) has_children[static_cast<size_t>(a.parents[j])] = true;
  Skeleton s;
  for (size_t j = 0; j < n; ++j) {
    Joint joint;
    joint.name = a.joint_names[j];
    joint.parent = a.parents[j];
    joint.offset = a.offsets.row(static_cast<Eigen::Index>(j)).transpose();
    joint.end_site = j > 0 && !has_children[j] &&
                     joint.name == a.joint_names[static_cast<size_t>(joint.parent)] + " End Site";
    if (j == 0 || (!joint.end_site && translation_moves(a, j)))
      joint.channels = {Channel::kXposition, Channel::kYposition, Channel::kZposition};
    if (!joint.end_site)
      joint.channels.insert(joint.channels.end(), {Channel::kZrotation, Channel::kXrotation, Channel::kYrotation});
    joint.first_channel = s.channel_count;
    s.channel_count += static_cast<int>(joint.channels.size());
    s.joints.push_back(joint);
  }
  return s;
}

}  // namespace

Clip clip_from_arrays(const TakeArrays& a, const std::string& source) {
  check_arrays(a, source);
  Clip clip;
  clip.source = source;
  clip.skeleton = skeleton_from_arrays(a);
  clip.frame_time = 1.0 / a.fps;
  const Eigen::Index frames = a.rotations.rows();
  clip.motion = MotionMatrix::Zero(frames, clip.skeleton.channel_count);
  for (size_t j = 0; j < clip.skeleton.joints.size(); ++j) {
    const Joint& joint = clip.skeleton.joints[j];
    if (joint.end_site) continue;
    const bool positions = is_position(joint.channels.front());
    if (positions && j > 0)
      clip.motion.block(0, joint.first_channel, frames, 3) = a.translations.block(0, 3 * j, frames, 3);
    const int rotation = joint.first_channel + (positions ? 3 : 0);
    Eigen::Vector3d previous = Eigen::Vector3d::Zero();
    for (Eigen::Index f = 0; f < frames; ++f) {
      const Eigen::Index c = 4 * static_cast<Eigen::Index>(j);
      Eigen::Quaterniond q(a.rotations(f, c), a.rotations(f, c + 1), a.rotations(f, c + 2), a.rotations(f, c + 3));
      if (!(q.norm() > 0.0))
        throw InputError(source + ": joint '" + joint.name + "' has a zero quaternion at frame " + std::to_string(f));
      const Eigen::Matrix3d r = q.normalized().toRotationMatrix();
      // Unwrapped against the frame before, so the angles have no jumps a resampling would blur.
      const Eigen::Vector3d angles =
          f == 0 ? matrix_to_euler(EulerOrder::kZXY, r) : matrix_to_euler_near(EulerOrder::kZXY, r, previous);
      clip.motion.block<1, 3>(f, rotation) = angles.transpose();
      previous = angles;
    }
  }
  clip.motion.block(0, 0, frames, 3) = a.root_positions;
  return clip;
}

TakeArrays arrays_from_clip(const Clip& clip) {
  const Skeleton& s = clip.skeleton;
  const Eigen::Index joints = static_cast<Eigen::Index>(s.joints.size());
  const Eigen::Index frames = clip.frames();
  TakeArrays a;
  a.fps = clip.fps();
  a.offsets.resize(joints, 3);
  a.rotations.resize(frames, 4 * joints);
  a.translations.resize(frames, 3 * joints);
  a.root_positions = Eigen::MatrixXd::Zero(frames, 3);
  for (Eigen::Index j = 0; j < joints; ++j) {
    const Joint& joint = s.joints[static_cast<size_t>(j)];
    a.joint_names.push_back(joint.name);
    a.parents.push_back(joint.parent);
    a.offsets.row(j) = joint.offset.transpose();
    Eigen::Quaterniond previous = Eigen::Quaterniond::Identity();
    for (Eigen::Index f = 0; f < frames; ++f) {
      const double* row = clip.motion.row(f).data();
      a.translations.block<1, 3>(f, 3 * j) = joint_local_translation(joint, row).transpose();
      Eigen::Quaterniond q(joint_local_rotation(joint, row));
      if (q.dot(previous) < 0.0) q.coeffs() = -q.coeffs();
      a.rotations.block<1, 4>(f, 4 * j) << q.w(), q.x(), q.y(), q.z();
      previous = q;
    }
  }
  for (Eigen::Index f = 0; f < frames && joints > 0; ++f)
    a.root_positions.row(f) = joint_local_translation(s.joints[0], clip.motion.row(f).data()).transpose();
  return a;
}

}  // namespace mostyle
