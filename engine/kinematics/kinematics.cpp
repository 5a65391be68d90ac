#include "engine/kinematics/kinematics.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <utility>

#include "engine/kinematics/euler.h"

namespace mostyle {

namespace {

// r * axis_rotation(axis, s, c) (the rotation whose sine and cosine they are), in place: only the two columns the rotation mixes change,
// each entry summed in the order the full product sums it (the same values).
inline __attribute__((always_inline)) void rotate_columns(Eigen::Matrix3d& r, int axis, double s, double c) {
  // axis_rotation's entries in the two columns it mixes (a, b): (m_aa, m_ba) and (m_ab, m_bb).
  const int a = axis == 0 ? 1 : 0, b = axis == 2 ? 1 : 2;
  const double m_ba = axis == 1 ? -s : s, m_ab = -m_ba;
  for (int i = 0; i < 3; ++i) {
    const double ra = r(i, a), rb = r(i, b);
    r(i, a) = ra * c + rb * m_ba;
    r(i, b) = ra * m_ab + rb * c;
  }
}

void rotate_columns(Eigen::Matrix3d& r, int axis, double degrees) {
  double s, c;
  sin_cos_degrees(degrees, &s, &c);
  rotate_columns(r, axis, s, c);
}

}  // namespace

Eigen::Matrix3d joint_local_rotation(const Joint& joint, const double* frame_values) {
  Eigen::Matrix3d r;
  bool first = true;
  for (size_t c = 0; c < joint.channels.size(); ++c) {
    const Channel ch = joint.channels[c];
    if (!is_rotation(ch)) continue;
    if (first) {
      r = axis_rotation(channel_axis(ch), frame_values[joint.first_channel + c]);
      first = false;
    } else {
      rotate_columns(r, channel_axis(ch), frame_values[joint.first_channel + c]);
    }
  }
  return first ? Eigen::Matrix3d::Identity() : r;
}

Eigen::Vector3d joint_local_translation(const Joint& joint, const double* frame_values) {
  // As Blender's importer does it (io_anim_bvh: a bone with location channels is
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

namespace {

// A joint joint_positions poses: its parent's slot, its rotation channels' axes and columns,
// where its translation comes from.
struct Posed {
  int parent = -1;                         // slot of its parent, -1 for a root
  std::vector<std::pair<int, int>> turns;  // (axis, column) in channel order
  bool has_position = false;
  std::array<int, 3> position{{-1, -1, -1}};  // column of each axis's position channel
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
};

// The joints to pose for `joints` (those and their ancestors), parents first, each once; *slot:
// per skeleton joint its place among them, -1 when not posed.
std::vector<Posed> posed_joints(const Skeleton& s, const std::vector<int>& joints, std::vector<int>* slot_out) {
  std::vector<int>& slot = *slot_out;
  slot.assign(s.joints.size(), -1);
  for (int j : joints)
    for (int p = j; p >= 0 && slot[static_cast<size_t>(p)] < 0; p = s.joints[static_cast<size_t>(p)].parent)
      slot[static_cast<size_t>(p)] = 0;  // marked; numbered below in skeleton order
  std::vector<Posed> posed;
  for (size_t i = 0; i < s.joints.size(); ++i) {
    if (slot[i] < 0) continue;
    const Joint& joint = s.joints[i];
    Posed p;
    p.parent = joint.parent >= 0 ? slot[static_cast<size_t>(joint.parent)] : -1;
    p.offset = joint.offset;
    for (size_t c = 0; c < joint.channels.size(); ++c) {
      const Channel ch = joint.channels[c];
      const int column = joint.first_channel + static_cast<int>(c);
      if (is_rotation(ch)) p.turns.push_back({channel_axis(ch), column});
      if (is_position(ch)) {
        p.has_position = true;
        p.position[static_cast<size_t>(channel_axis(ch))] = column;
      }
    }
    slot[i] = static_cast<int>(posed.size());
    posed.push_back(std::move(p));
  }
  return posed;
}

}  // namespace

Eigen::MatrixXd joint_positions(const Clip& clip, const std::vector<int>& joints) {
  std::vector<int> slot;
  const std::vector<Posed> posed = posed_joints(clip.skeleton, joints, &slot);
  // The rotation channels' columns, each posed joint's in channel order, one after another.
  std::vector<int> turn_columns;
  for (const Posed& p : posed)
    for (const auto& turn : p.turns) turn_columns.push_back(turn.second);
  // Per block of frames, the sines and cosines of its rotation channels at once (the same values
  // as one at a time, several times faster: sin_cos_degrees_n), then per frame each posed joint
  // as frame_pose poses it (joint_local_rotation's and joint_local_translation's arithmetic, the
  // same values).
  constexpr int kBlock = 64;
  const size_t turns = turn_columns.size();
  std::vector<double> angles(turns * kBlock), sines(turns * kBlock), cosines(turns * kBlock);
  Eigen::MatrixXd out(clip.frames(), 3 * static_cast<Eigen::Index>(joints.size()));
  std::vector<Eigen::Matrix3d> rotations(posed.size());
  std::vector<Eigen::Vector3d> positions(posed.size());
  for (int first = 0; first < clip.frames(); first += kBlock) {
    const int block = std::min(kBlock, clip.frames() - first);
    for (int b = 0; b < block; ++b) {
      const double* values = clip.motion.row(first + b).data();
      for (size_t t = 0; t < turns; ++t) angles[static_cast<size_t>(b) * turns + t] = values[turn_columns[t]];
    }
    sin_cos_degrees_n(angles.data(), static_cast<size_t>(block) * turns, sines.data(), cosines.data());
    for (int b = 0; b < block; ++b) {
      const int f = first + b;
      const double* values = clip.motion.row(f).data();
      const double* s = sines.data() + static_cast<size_t>(b) * turns;
      const double* c = cosines.data() + static_cast<size_t>(b) * turns;
      for (size_t k = 0; k < posed.size(); ++k) {
        const Posed& p = posed[k];
        Eigen::Matrix3d local = Eigen::Matrix3d::Identity();
        for (size_t t = 0; t < p.turns.size(); ++t, ++s, ++c) {
          if (t == 0) local = axis_rotation(p.turns[t].first, *s, *c);
          else rotate_columns(local, p.turns[t].first, *s, *c);
        }
        Eigen::Vector3d at = p.offset;
        if (p.has_position)
          for (int a = 0; a < 3; ++a)
            at[a] = p.position[static_cast<size_t>(a)] >= 0 ? values[p.position[static_cast<size_t>(a)]] : 0.0;
        if (p.parent < 0) {
          rotations[k] = local;
          positions[k] = at;
        } else {
          rotations[k] = rotations[static_cast<size_t>(p.parent)] * local;
          positions[k] = positions[static_cast<size_t>(p.parent)] + rotations[static_cast<size_t>(p.parent)] * at;
        }
      }
      for (size_t i = 0; i < joints.size(); ++i)
        out.block<1, 3>(f, 3 * static_cast<Eigen::Index>(i)) =
            positions[static_cast<size_t>(slot[static_cast<size_t>(joints[i])])].transpose();
    }
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
