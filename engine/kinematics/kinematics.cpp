#include "engine/kinematics/kinematics.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cstring>
#include <utility>

#include "engine/kinematics/euler.h"
#include "engine/kinematics/four_lanes.h"

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

void place_joint(const Skeleton& skeleton, int j, const Eigen::Matrix3d& local_rotation,
                 const Eigen::Vector3d& local_translation, Pose* pose) {
  const int parent = skeleton.joints[static_cast<size_t>(j)].parent;
  assert(parent < j && "joints must come after their parent");
  Eigen::Matrix3d& rotation = pose->rotations[static_cast<size_t>(j)];
  Eigen::Vector3d& position = pose->positions[static_cast<size_t>(j)];
  if (parent < 0) {
    rotation = local_rotation;
    position = local_translation;
  } else {
    const Eigen::Matrix3d& parent_rotation = pose->rotations[static_cast<size_t>(parent)];
    rotation = parent_rotation * local_rotation;
    position = pose->positions[static_cast<size_t>(parent)] + parent_rotation * local_translation;
  }
}

void pose_frame(const Skeleton& skeleton, const double* values, const std::vector<int>& chain, Pose* pose) {
  for (int j : chain) {
    const Joint& joint = skeleton.joints[static_cast<size_t>(j)];
    place_joint(skeleton, j, joint_local_rotation(joint, values), joint_local_translation(joint, values), pose);
  }
}

void pose_frame(const Skeleton& skeleton, const double* values, Pose* pose) {
  const size_t n = skeleton.joints.size();
  pose->rotations.resize(n);
  pose->positions.resize(n);
  for (size_t j = 0; j < n; ++j) {
    const Joint& joint = skeleton.joints[j];
    place_joint(skeleton, static_cast<int>(j), joint_local_rotation(joint, values),
                joint_local_translation(joint, values), pose);
  }
}

Eigen::MatrixXd joint_positions(const Clip& clip) {
  const Skeleton& s = clip.skeleton;
  const int n = static_cast<int>(s.joints.size());
  Eigen::MatrixXd out(clip.frames(), 3 * n);
  Pose pose;
  for (int f = 0; f < clip.frames(); ++f) {
    pose_frame(s, clip.motion.row(f).data(), &pose);
    for (int i = 0; i < n; ++i) out.block<1, 3>(f, 3 * i) = pose.positions[i].transpose();
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
  bool leaf = false;  // no posed joint below it: only its position is needed, not its rotation
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
  // A leaf's own rotation moves nothing posed: its angles are not read.
  std::vector<char> has_child(posed.size(), 0);
  for (const Posed& p : posed)
    if (p.parent >= 0) has_child[static_cast<size_t>(p.parent)] = 1;
  for (size_t k = 0; k < posed.size(); ++k)
    if (!has_child[k]) {
      posed[k].leaf = true;
      posed[k].turns.clear();
    }
  return posed;
}

}  // namespace

namespace {

// Four doubles kept in memory that may not be aligned to their size (a vector's heap).
typedef double StoredDoubles4 __attribute__((vector_size(32), aligned(8)));

// One posed joint's global rotation (row by row) and position at four frames.
struct Lanes4 {
  StoredDoubles4 r[9];
  StoredDoubles4 p[3];
};

// The helpers below are always inlined, so no four-lane value crosses a call: GCC's note that
// one would be passed differently with and without AVX does not apply.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

inline __attribute__((always_inline)) Doubles4 broadcast(double x) { return Doubles4{x, x, x, x}; }

// axis_rotation's entries (row by row) from four angles' sines and cosines.
inline __attribute__((always_inline)) void axis_rotation4(int axis, Doubles4 s, Doubles4 c, Doubles4* m) {
  const Doubles4 zero = broadcast(0.0), one = broadcast(1.0);
  switch (axis) {
    case 0: m[0] = one, m[1] = zero, m[2] = zero, m[3] = zero, m[4] = c, m[5] = -s, m[6] = zero, m[7] = s, m[8] = c; break;
    case 1: m[0] = c, m[1] = zero, m[2] = s, m[3] = zero, m[4] = one, m[5] = zero, m[6] = -s, m[7] = zero, m[8] = c; break;
    default: m[0] = c, m[1] = -s, m[2] = zero, m[3] = s, m[4] = c, m[5] = zero, m[6] = zero, m[7] = zero, m[8] = one; break;
  }
}

// rotate_columns on four frames (row by row entries), the same arithmetic.
inline __attribute__((always_inline)) void rotate_columns4(Doubles4* r, int axis, Doubles4 s, Doubles4 c) {
  const int a = axis == 0 ? 1 : 0, b = axis == 2 ? 1 : 2;
  const Doubles4 m_ba = axis == 1 ? -s : s, m_ab = -m_ba;
  for (int i = 0; i < 3; ++i) {
    const Doubles4 ra = r[3 * i + a], rb = r[3 * i + b];
    r[3 * i + a] = ra * c + rb * m_ba;
    r[3 * i + b] = ra * m_ab + rb * c;
  }
}

// Row i of a 3x3 product's sum, in Eigen's order for fixed 3x3 products compiled for SSE2 (the
// first two rows a packet, summed from the first term; the third row a scalar reduction, summed
// from the last): (t0 + t1) + t2 for rows 0 and 1, t0 + (t1 + t2) for row 2.
inline __attribute__((always_inline)) Doubles4 row_sum(int i, Doubles4 t0, Doubles4 t1, Doubles4 t2) {
  return i < 2 ? (t0 + t1) + t2 : t0 + (t1 + t2);
}

// parent's position plus its rotation times `at`, as Eigen sums it.
inline __attribute__((always_inline)) void place4(const Lanes4& parent, const Doubles4* at, StoredDoubles4* p) {
  for (int i = 0; i < 3; ++i)
    p[i] = parent.p[i] + row_sum(i, parent.r[3 * i] * at[0], parent.r[3 * i + 1] * at[1], parent.r[3 * i + 2] * at[2]);
}

// The rotation channels of a block's frames, gathered for sin_cos_degrees_n, then FK of the posed
// joints four frames at a time in the order joint_positions(clip) poses each (the same values).
struct BlockFk {
  static constexpr int kBlock = 64;  // frames per block, a multiple of four
  const Clip& clip;
  const std::vector<Posed>& posed;
  const std::vector<int>& joints;    // the joints asked for
  const std::vector<int>& slot;
  std::vector<int> turn_columns;     // each posed joint's rotation channels, one after another
  std::vector<double> angles, sines, cosines;  // [turn][frame in block]
  std::vector<Lanes4> lanes;         // per posed joint

  BlockFk(const Clip& c, const std::vector<Posed>& p, const std::vector<int>& j, const std::vector<int>& s)
      : clip(c), posed(p), joints(j), slot(s) {
    for (const Posed& q : posed)
      for (const auto& turn : q.turns) turn_columns.push_back(turn.second);
    const size_t n = turn_columns.size() * kBlock;
    angles.assign(n, 0.0);
    sines.assign(n, 0.0);
    cosines.assign(n, 0.0);
    lanes.resize(posed.size());
  }

  // Frames [first, first + block): rows past the clip's end repeat its last frame (not stored).
  const double* row(int frame) const { return clip.motion.row(std::min(frame, clip.frames() - 1)).data(); }

  void angles_of(int first) {
    for (size_t t = 0; t < turn_columns.size(); ++t)
      for (int b = 0; b < kBlock; ++b) angles[t * kBlock + static_cast<size_t>(b)] = row(first + b)[turn_columns[t]];
    sin_cos_degrees_n(angles.data(), angles.size(), sines.data(), cosines.data());
  }

  // Four frames from `frame` (b: its place in the block).
  inline __attribute__((always_inline)) void pose4(int frame, int b, Eigen::MatrixXd& out) {
    const double* rows[4] = {row(frame), row(frame + 1), row(frame + 2), row(frame + 3)};
    size_t turn = 0;
    for (size_t k = 0; k < posed.size(); ++k) {
      const Posed& p = posed[k];
      Doubles4 at[3];
      for (int a = 0; a < 3; ++a) {
        const int column = p.position[static_cast<size_t>(a)];
        at[a] = !p.has_position ? broadcast(p.offset[a])
                : column >= 0   ? Doubles4{rows[0][column], rows[1][column], rows[2][column], rows[3][column]}
                                : broadcast(0.0);
      }
      Lanes4& l = lanes[k];
      if (p.leaf) {
        if (p.parent < 0) for (int a = 0; a < 3; ++a) l.p[a] = at[a];
        else place4(lanes[static_cast<size_t>(p.parent)], at, l.p);
        continue;
      }
      Doubles4 local[9];
      if (p.turns.empty()) axis_rotation4(0, broadcast(0.0), broadcast(1.0), local);  // the identity
      for (size_t t = 0; t < p.turns.size(); ++t, ++turn) {
        Doubles4 s, c;
        std::memcpy(&s, sines.data() + turn * kBlock + static_cast<size_t>(b), sizeof s);
        std::memcpy(&c, cosines.data() + turn * kBlock + static_cast<size_t>(b), sizeof c);
        if (t == 0) axis_rotation4(p.turns[t].first, s, c, local);
        else rotate_columns4(local, p.turns[t].first, s, c);
      }
      if (p.parent < 0) {
        for (int e = 0; e < 9; ++e) l.r[e] = local[e];
        for (int a = 0; a < 3; ++a) l.p[a] = at[a];
      } else {
        const Lanes4& q = lanes[static_cast<size_t>(p.parent)];
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j)
            l.r[3 * i + j] = row_sum(i, q.r[3 * i] * local[j], q.r[3 * i + 1] * local[3 + j], q.r[3 * i + 2] * local[6 + j]);
        place4(q, at, l.p);
      }
    }
    // Column-major output: four frames of one coordinate are contiguous.
    const int stored = std::min(4, clip.frames() - frame);
    for (size_t i = 0; i < joints.size(); ++i) {
      const Lanes4& l = lanes[static_cast<size_t>(slot[static_cast<size_t>(joints[i])])];
      for (int a = 0; a < 3; ++a) {
        double* to = out.data() + (3 * static_cast<Eigen::Index>(i) + a) * out.rows() + frame;
        if (stored == 4) std::memcpy(to, &l.p[a], sizeof(Doubles4));
        else for (int e = 0; e < stored; ++e) to[e] = l.p[a][e];
      }
    }
  }

  inline __attribute__((always_inline)) void run(Eigen::MatrixXd& out) {
    for (int first = 0; first < clip.frames(); first += kBlock) {
      angles_of(first);
      for (int b = 0; b < kBlock && first + b < clip.frames(); b += 4) pose4(first + b, b, out);
    }
  }
};

#if defined(__x86_64__)
__attribute__((target("avx2"))) void block_fk_avx2(BlockFk& fk, Eigen::MatrixXd& out) { fk.run(out); }
#endif
void block_fk_baseline(BlockFk& fk, Eigen::MatrixXd& out) { fk.run(out); }

}  // namespace

// Chosen at the first call, not by the loader (an ifunc resolver runs before the sanitizers'
// runtimes are up).
Eigen::MatrixXd joint_positions(const Clip& clip, const std::vector<int>& joints) {
  std::vector<int> slot;
  const std::vector<Posed> posed = posed_joints(clip.skeleton, joints, &slot);
  Eigen::MatrixXd out(clip.frames(), 3 * static_cast<Eigen::Index>(joints.size()));
  if (clip.frames() == 0 || joints.empty()) return out;
  BlockFk fk(clip, posed, joints, slot);
#if defined(__x86_64__)
  static const bool avx2 = __builtin_cpu_supports("avx2");
  if (avx2) {
    block_fk_avx2(fk, out);
    return out;
  }
#endif
  block_fk_baseline(fk, out);
  return out;
}

Pose pose_at(const Clip& clip, int frame) {
  assert(frame >= 0 && frame < clip.frames());
  Pose pose;
  pose_frame(clip.skeleton, clip.motion.row(frame).data(), &pose);
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

std::vector<int> chain_joints(const Skeleton& skeleton, const std::vector<int>& joints) {
  std::vector<char> needed(skeleton.joints.size(), 0);
  for (int j : joints)
    for (int p = j; p >= 0 && !needed[static_cast<size_t>(p)]; p = skeleton.joints[static_cast<size_t>(p)].parent)
      needed[static_cast<size_t>(p)] = 1;
  std::vector<int> out;
  for (size_t j = 0; j < needed.size(); ++j)
    if (needed[j]) out.push_back(static_cast<int>(j));
  return out;
}

}  // namespace mostyle
