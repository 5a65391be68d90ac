#include "engine/io/scene_animation.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/base/error.h"
#include "engine/kinematics/euler.h"

namespace mostyle {
namespace {

// How far (relative to the skeleton's size, or to 1 for a scale) keys may lie off the rest pose
// before a joint's offset counts as moving: exporters key the rest translation again with
// float32 noise and rounding of some 1e-5 (FK then misses the file's positions by at most this).
constexpr double kRestTolerance = 1e-4;
// A fraction of a frame that float32 key times may miss a frame by.
constexpr double kFrameTolerance = 1e-3;
// The most frames a take may be sampled into, whatever the memory limit (a typing slip in --fps
// or a key at 1e30 s).
constexpr double kMaxFrames = 1e8;

std::string take_label(const AnimatedScene& scene, int take) {
  return scene.source + ": animation '" + scene.takes[take].name + "'";
}

int track_width(TrackTarget target) { return target == TrackTarget::kRotation ? 4 : 3; }

const char* target_name(TrackTarget target) {
  switch (target) {
    case TrackTarget::kTranslation: return "translation";
    case TrackTarget::kRotation: return "rotation";
    case TrackTarget::kScale: return "scale";
  }
  return "?";
}

// Row k of a track's values (the value row for cubic splines).
// Row r of a track's values, the 4th entry 0 for 3-wide tracks.
Eigen::Vector4d value_row(const KeyTrack& track, Eigen::Index r) {
  Eigen::Vector4d v = Eigen::Vector4d::Zero();
  for (Eigen::Index c = 0; c < track.values.cols() && c < 4; ++c) v(c) = track.values(r, c);
  return v;
}

Eigen::Vector4d key_value(const KeyTrack& track, Eigen::Index k) {
  return value_row(track, track.interpolation == KeyInterpolation::kCubicSpline ? 3 * k + 1 : k);
}

Eigen::Vector4d normalized_if_rotation(const KeyTrack& track, const Eigen::Vector4d& v) {
  if (track.target != TrackTarget::kRotation) return v;
  const double n = v.norm();
  if (n > 0 && std::isfinite(n)) return v / n;
  return Eigen::Vector4d(0, 0, 0, 1);
}

Eigen::Quaterniond as_quaternion(const Eigen::Vector4d& v) { return Eigen::Quaterniond(v(3), v(0), v(1), v(2)); }

void check_track(const AnimatedScene& scene, int take, const KeyTrack& track) {
  const auto fail = [&](const std::string& what) {
    const std::string node =
        track.node >= 0 && track.node < static_cast<int>(scene.nodes.size()) ? scene.nodes[track.node].name : "?";
    throw InputError(take_label(scene, take) + ": the " + target_name(track.target) + " keys of node '" + node +
                     "' " + what);
  };
  if (track.node < 0 || track.node >= static_cast<int>(scene.nodes.size()))
    throw InputError(take_label(scene, take) + ": a track targets node " + std::to_string(track.node) +
                     ", which the file does not have");
  const Eigen::Index keys = static_cast<Eigen::Index>(track.times.size());
  if (keys == 0) fail("are empty");
  const Eigen::Index rows = track.interpolation == KeyInterpolation::kCubicSpline ? 3 * keys : keys;
  if (track.values.rows() != rows || track.values.cols() != track_width(track.target))
    fail("have " + std::to_string(track.values.rows()) + " values for " + std::to_string(keys) + " times");
  for (Eigen::Index k = 0; k < keys; ++k) {
    if (!std::isfinite(track.times[k])) fail("have a time that is not a finite number");
    if (k > 0 && !(track.times[k] > track.times[k - 1]))
      fail("have times that do not increase (key " + std::to_string(k) + ")");
  }
  if (!track.values.allFinite()) fail("have a value that is not a finite number");
}

// Rotation part of a linear map with positive scales: Gram-Schmidt on its columns (exact for
// T*R*S chains with uniform scale; the nearest rotation's stand-in otherwise).
Eigen::Matrix3d rotation_part(const Eigen::Matrix3d& m) {
  Eigen::Vector3d x = m.col(0), y = m.col(1);
  const double nx = x.norm();
  if (!(nx > 0)) return Eigen::Matrix3d::Identity();
  x /= nx;
  y -= x.dot(y) * x;
  const double ny = y.norm();
  if (!(ny > 0)) return Eigen::Matrix3d::Identity();
  y /= ny;
  Eigen::Matrix3d r;
  r.col(0) = x;
  r.col(1) = y;
  r.col(2) = x.cross(y);
  return r;
}

}  // namespace

std::vector<TakeInfo> scene_take_infos(const AnimatedScene& scene) {
  // How many of the skeleton's joints each take keys; unknown when the take has no one skeleton
  // (reading it then says why).
  const auto joints_of = [&](int take) {
    std::vector<int> joint_of;
    try {
      const SceneSkeleton skeleton = scene_skeleton(scene, take);
      joint_of.assign(scene.nodes.size(), -1);
      for (size_t j = 0; j < skeleton.nodes.size(); ++j) joint_of[skeleton.nodes[j]] = static_cast<int>(j);
    } catch (const InputError&) {
    }
    return joint_of;
  };
  const std::vector<int> file_joints = joints_of(-1);
  std::vector<TakeInfo> out;
  for (size_t k = 0; k < scene.takes.size(); ++k) {
    const SceneTake& take = scene.takes[k];
    const std::vector<int> joint_of = file_joints.empty() ? joints_of(static_cast<int>(k)) : file_joints;
    TakeInfo info;
    info.name = take.name;
    double first = std::numeric_limits<double>::infinity(), last = -first;
    std::vector<char> keyed(joint_of.size(), 0);
    for (const KeyTrack& t : take.tracks) {
      if (t.times.empty()) continue;
      first = std::min(first, t.times.front());
      last = std::max(last, t.times.back());
      info.keyframes = std::max(info.keyframes, static_cast<int>(t.times.size()));
      if (t.node >= 0 && t.node < static_cast<int>(joint_of.size()) && joint_of[t.node] >= 0) keyed[t.node] = 1;
    }
    info.seconds = last >= first && std::isfinite(last - first) ? last - first : 0.0;
    info.moves = joint_of.empty() ? -1 : static_cast<int>(std::count(keyed.begin(), keyed.end(), 1));
    out.push_back(info);
  }
  return out;
}

int find_take(const AnimatedScene& scene, const std::string& name) {
  for (size_t i = 0; i < scene.takes.size(); ++i)
    if (scene.takes[i].name == name) return static_cast<int>(i);
  return -1;
}

Eigen::Vector4d sample_track(const KeyTrack& track, double t, double snap) {
  const auto& times = track.times;
  const Eigen::Index keys = static_cast<Eigen::Index>(times.size());
  if (t <= times.front() + snap || keys == 1) return normalized_if_rotation(track, key_value(track, 0));
  if (t >= times.back() - snap) return normalized_if_rotation(track, key_value(track, keys - 1));
  // k: the last key at or before t, so times[k] <= t < times[k + 1].
  const Eigen::Index k = std::upper_bound(times.begin(), times.end(), t) - times.begin() - 1;
  if (t - times[k] <= snap) return normalized_if_rotation(track, key_value(track, k));
  if (times[k + 1] - t <= snap) return normalized_if_rotation(track, key_value(track, k + 1));
  const double t0 = times[k], t1 = times[k + 1], dt = t1 - t0;
  const double s = (t - t0) / dt;
  switch (track.interpolation) {
    case KeyInterpolation::kStep: return normalized_if_rotation(track, key_value(track, k));
    case KeyInterpolation::kLinear: {
      const Eigen::Vector4d a = key_value(track, k), b = key_value(track, k + 1);
      if (track.target != TrackTarget::kRotation) return (1 - s) * a + s * b;
      const Eigen::Quaterniond q = as_quaternion(normalized_if_rotation(track, a))
                                       .slerp(s, as_quaternion(normalized_if_rotation(track, b)));
      return normalized_if_rotation(track, Eigen::Vector4d(q.x(), q.y(), q.z(), q.w()));
    }
    case KeyInterpolation::kCubicSpline: {
      // glTF 2.0 Appendix C: p(s) = (2s^3 - 3s^2 + 1) v_k + dt (s^3 - 2s^2 + s) b_k
      //                            + (-2s^3 + 3s^2) v_k+1 + dt (s^3 - s^2) a_k+1,
      // b_k the out-tangent of key k, a_k+1 the in-tangent of key k+1.
      const double s2 = s * s, s3 = s2 * s;
      const Eigen::Vector4d v0 = value_row(track, 3 * k + 1), b0 = value_row(track, 3 * k + 2);
      const Eigen::Vector4d v1 = value_row(track, 3 * (k + 1) + 1), a1 = value_row(track, 3 * (k + 1));
      const Eigen::Vector4d p = (2 * s3 - 3 * s2 + 1) * v0 + dt * (s3 - 2 * s2 + s) * b0 +
                                (-2 * s3 + 3 * s2) * v1 + dt * (s3 - s2) * a1;
      return normalized_if_rotation(track, p);
    }
  }
  return key_value(track, k);
}

double default_take_rate(const AnimatedScene& scene, int take) {
  if (scene.frame_rate > 0 && std::isfinite(scene.frame_rate)) return scene.frame_rate;
  const auto usable = [](double rate) { return rate >= 1.0 && rate <= 1000.0; };
  // Evenly spaced keys: their exact rate, so every sample lands on a key.
  const KeyTrack* longest = nullptr;
  for (const KeyTrack& t : scene.takes[take].tracks)
    if (longest == nullptr || t.times.size() > longest->times.size()) longest = &t;
  if (longest != nullptr && longest->times.size() >= 3) {
    const auto& times = longest->times;
    const double step = (times.back() - times.front()) / static_cast<double>(times.size() - 1);
    bool even = step > 0 && std::isfinite(step);
    for (size_t k = 1; k < times.size() && even; ++k)
      even = std::abs(times[k] - times[k - 1] - step) <= 0.01 * step;
    if (even && usable(1.0 / step)) return 1.0 / step;
  }
  std::vector<double> spacing;
  for (const KeyTrack& t : scene.takes[take].tracks) {
    for (size_t k = 1; k < t.times.size() && spacing.size() < 100000; ++k) {
      const double d = t.times[k] - t.times[k - 1];
      if (d > 0 && std::isfinite(d)) spacing.push_back(d);
    }
  }
  if (spacing.empty()) return 30.0;
  std::nth_element(spacing.begin(), spacing.begin() + spacing.size() / 2, spacing.end());
  const double rate = frame_rate_from_frame_time(spacing[spacing.size() / 2]);
  // A rate from keys far apart (a pose every few seconds) or far too dense is no capture rate.
  return usable(rate) ? rate : 30.0;
}

namespace {

// "'A', 'B', 'C'": up to three node names.
std::string node_list(const AnimatedScene& scene, const std::vector<int>& nodes) {
  std::string list;
  for (size_t i = 0; i < nodes.size() && i < 3; ++i) list += (i ? ", '" : "'") + scene.nodes[nodes[i]].name + "'";
  return list;
}

// Whether a joint's offset leaves its rest offset in some take: translation keys off the rest
// translation (tangents of a spline that are not zero), in world units.
bool translation_moves(const KeyTrack& track, const SceneNode& node, double parent_scale, double tolerance) {
  if (track.values.cols() != 3) return false;
  const bool cubic = track.interpolation == KeyInterpolation::kCubicSpline;
  for (Eigen::Index r = 0; r < track.values.rows(); ++r) {
    const Eigen::Vector3d v = track.values.row(r).transpose();
    const bool tangent = cubic && r % 3 != 1;
    const double off = tangent ? v.norm() : (v - node.translation).norm();
    if (off * parent_scale > tolerance) return true;
  }
  return false;
}

// Whether scale keys leave the rest scale (relative), which moves the offsets of the joints below.
bool scale_moves(const KeyTrack& track, const SceneNode& node) {
  if (track.values.cols() != 3) return false;
  const bool cubic = track.interpolation == KeyInterpolation::kCubicSpline;
  for (Eigen::Index r = 0; r < track.values.rows(); ++r) {
    const Eigen::Vector3d v = track.values.row(r).transpose();
    const bool tangent = cubic && r % 3 != 1;
    const Eigen::Vector3d off = tangent ? v : Eigen::Vector3d(v - node.scale);
    if (off.cwiseAbs().maxCoeff() > kRestTolerance * std::max(1.0, node.scale.cwiseAbs().maxCoeff())) return true;
  }
  return false;
}

// Each node's depth below the scene's top. Throws InputError on a node before its parent.
std::vector<int> node_depths(const AnimatedScene& scene) {
  const int n = static_cast<int>(scene.nodes.size());
  std::vector<int> depth(n, 0);
  for (int i = 0; i < n; ++i) {
    if (scene.nodes[i].parent >= i)
      throw InputError(scene.source + ": node '" + scene.nodes[i].name + "' comes before its parent");
    depth[i] = scene.nodes[i].parent < 0 ? 0 : depth[scene.nodes[i].parent] + 1;
  }
  return depth;
}

// The skeleton's members: the skins' joints (skeleton.from_skins set); else every node any take
// keys. Throws InputError on a track whose node the file lacks, or no member.
std::vector<char> skeleton_members(const AnimatedScene& scene, SceneSkeleton& skeleton) {
  const int n = static_cast<int>(scene.nodes.size());
  std::vector<char> member(n, 0);
  for (int node : scene.skin_joints) {
    if (node < 0 || node >= n) continue;
    member[node] = 1;
    skeleton.from_skins = true;
  }
  if (!skeleton.from_skins) {
    for (size_t t = 0; t < scene.takes.size(); ++t) {
      for (const KeyTrack& track : scene.takes[t].tracks) {
        if (track.node < 0 || track.node >= n)
          throw InputError(take_label(scene, static_cast<int>(t)) + ": a track targets node " +
                           std::to_string(track.node) + ", which the file does not have");
        member[track.node] = 1;
      }
    }
  }
  if (std::none_of(member.begin(), member.end(), [](char m) { return m != 0; }))
    throw InputError(scene.source + ": no animation keys a node: no skeleton moves in it");
  return member;
}

// The members' lowest common ancestor; -1 when they have none but the scene root that holds
// everything (assimp's), which is no skeleton's root unless it is a member.
int common_root(const AnimatedScene& scene, const std::vector<int>& depth, const std::vector<char>& in) {
  int root = -1;
  for (int i = 0; i < static_cast<int>(in.size()); ++i) {
    if (!in[i]) continue;
    if (root < 0) {
      root = i;
      continue;
    }
    int a = root, b = i;
    while (a != b && a >= 0 && b >= 0) {
      if (depth[a] >= depth[b]) a = scene.nodes[a].parent;
      else b = scene.nodes[b].parent;
    }
    if (a != b) return -1;
    root = a;
  }
  return root == scene.scene_root && root >= 0 && !in[root] ? -1 : root;
}

// Several skeletons (characters) in one file: the members kept to the one whose members the
// take keys, when it keys one only; their root, or -1.
int keyed_character_root(const AnimatedScene& scene, int take, const std::vector<int>& depth,
                         std::vector<char>& member) {
  const int n = static_cast<int>(scene.nodes.size());
  const auto top_of = [&](int i) {
    while (scene.nodes[i].parent >= 0 && scene.nodes[i].parent != scene.scene_root) i = scene.nodes[i].parent;
    return i;
  };
  std::vector<int> tops;
  for (const KeyTrack& track : scene.takes[take].tracks)
    if (track.node >= 0 && track.node < n && std::find(tops.begin(), tops.end(), top_of(track.node)) == tops.end())
      tops.push_back(top_of(track.node));
  if (tops.size() != 1) return -1;
  for (int i = 0; i < n; ++i)
    if (member[i] && top_of(i) != tops.front()) member[i] = 0;
  return common_root(scene, depth, member);
}

// Throws the InputError that names the several skeletons the members form.
[[noreturn]] void fail_several_skeletons(const AnimatedScene& scene, int take, const SceneSkeleton& skeleton,
                                         const std::vector<char>& member) {
  const std::string members = skeleton.from_skins ? "the skins' joints" : "the animations' nodes";
  std::vector<int> tops;
  for (int i = 0; i < static_cast<int>(member.size()); ++i) {
    if (!member[i]) continue;
    int up = scene.nodes[i].parent;
    while (up >= 0 && !member[up]) up = scene.nodes[up].parent;
    if (up < 0) tops.push_back(i);
  }
  throw InputError(scene.source + ": " + members + " form several skeletons (rooted at " + node_list(scene, tops) +
                   ")" + (take >= 0 ? " and animation '" + scene.takes[take].name + "' moves more than one" : "") +
                   ": keep one per file");
}

// The members and the nodes between them and the root, depth first from the root.
std::vector<int> skeleton_nodes(const AnimatedScene& scene, const std::vector<char>& member, int root) {
  const int n = static_cast<int>(scene.nodes.size());
  std::vector<char> in_skeleton(n, 0);
  for (int i = 0; i < n; ++i) {
    if (!member[i]) continue;
    for (int up = i; up >= 0 && !in_skeleton[up]; up = scene.nodes[up].parent) {
      in_skeleton[up] = 1;
      if (up == root) break;
    }
  }
  std::vector<std::vector<int>> children(n);
  for (int i = 0; i < n; ++i)
    if (in_skeleton[i] && i != root) children[scene.nodes[i].parent].push_back(i);
  std::vector<int> nodes;
  std::vector<int> stack{root};
  while (!stack.empty()) {
    const int node = stack.back();
    stack.pop_back();
    nodes.push_back(node);
    for (auto it = children[node].rbegin(); it != children[node].rend(); ++it) stack.push_back(*it);
  }
  return nodes;
}

// The limbs that hang from the skeleton with only limbs between, made members: end bones no
// take keys (FBX files keep them as LimbNodes, which Blender imports as bones).
void add_hanging_limbs(const AnimatedScene& scene, const std::vector<int>& nodes, std::vector<char>& member) {
  std::vector<char> in(scene.nodes.size(), 0);
  for (int node : nodes) in[node] = 1;
  for (size_t i = 0; i < scene.nodes.size(); ++i) {  // parents come first
    const int parent = scene.nodes[i].parent;
    if (in[i] || !scene.nodes[i].limb || parent < 0 || !in[parent]) continue;
    in[i] = 1;
    member[i] = 1;
  }
}

}  // namespace

SceneSkeleton scene_skeleton(const AnimatedScene& scene, int take) {
  const std::vector<int> depth = node_depths(scene);
  SceneSkeleton skeleton;
  std::vector<char> member = skeleton_members(scene, skeleton);
  int root = common_root(scene, depth, member);
  if (root < 0 && take >= 0 && take < static_cast<int>(scene.takes.size()))
    root = keyed_character_root(scene, take, depth, member);
  if (root < 0) fail_several_skeletons(scene, take, skeleton, member);
  skeleton.nodes = skeleton_nodes(scene, member, root);
  const size_t found = std::count(member.begin(), member.end(), 1);
  add_hanging_limbs(scene, skeleton.nodes, member);
  if (static_cast<size_t>(std::count(member.begin(), member.end(), 1)) != found)
    skeleton.nodes = skeleton_nodes(scene, member, root);
  return skeleton;
}

namespace {

// The nodes of a take's skeleton and the poses of its joints, in world and in their parents'
// frames, at one time or at rest.
class SkeletonPoser {
 public:
  // Throws InputError when the take keys none of the skeleton's joints nor a node above them.
  SkeletonPoser(const AnimatedScene& scene, int take, const SceneSkeleton& skeleton)
      : scene_(scene), order_(skeleton.nodes) {
    const SceneTake& st = scene.takes[take];
    const int n = static_cast<int>(scene.nodes.size());
    const int root = skeleton.root();
    const int joints = static_cast<int>(order_.size());
    joint_of_.assign(n, -1);
    for (int j = 0; j < joints; ++j) joint_of_[order_[j]] = j;
    // Nodes whose transforms matter: the skeleton and everything above its root.
    needed_.assign(n, 0);
    for (int node : order_) needed_[node] = 1;
    for (int up = scene.nodes[root].parent; up >= 0; up = scene.nodes[up].parent) needed_[up] = 1;
    if (std::none_of(st.tracks.begin(), st.tracks.end(), [&](const KeyTrack& t) { return needed_[t.node] != 0; }))
      throw InputError(take_label(scene, take) + " keys none of the skeleton's joints (rooted at '" +
                       scene.nodes[root].name + "') nor a node above them");
    track_of_.assign(3 * static_cast<size_t>(n), nullptr);
    for (const KeyTrack& t : st.tracks) track_of_[3 * t.node + static_cast<int>(t.target)] = &t;
    global_.assign(n, Eigen::Affine3d::Identity());
    rot_.resize(joints);
    pos_.resize(joints);
    parent_joint_.assign(joints, -1);
    for (int j = 1; j < joints; ++j) parent_joint_[j] = joint_of_[scene.nodes[order_[j]].parent];
  }
  int joints() const { return static_cast<int>(order_.size()); }
  int node(int joint) const { return order_[joint]; }
  int joint_of(int node) const { return joint_of_[node]; }
  bool needed(int node) const { return needed_[node] != 0; }
  int parent_joint(int joint) const { return parent_joint_[joint]; }
  const Eigen::Matrix3d& rotation(int joint) const { return rot_[joint]; }  // world, orthonormal
  const Eigen::Vector3d& position(int joint) const { return pos_[joint]; }  // world

  // World rotations (orthonormal) and positions of the joints at time t (keys within snap
  // seconds of t read as at t), or at rest (no track read). Computed twice per frame (once to
  // find the joints whose offsets change, once to write the channels) rather than kept for all
  // frames: that store took more memory than the clip and its page faults most of the time on a
  // 20 MB file.
  void pose(double t, double snap, bool rest) {
    for (int i = 0; i < static_cast<int>(scene_.nodes.size()); ++i) {
      if (!needed_[i]) continue;
      const SceneNode& node = scene_.nodes[i];
      Eigen::Vector3d tr = node.translation, sc = node.scale;
      Eigen::Quaterniond q = node.rotation;
      if (!rest) {
        if (const KeyTrack* k = track_of_[3 * i]) tr = sample_track(*k, t, snap).head<3>();
        if (const KeyTrack* k = track_of_[3 * i + 1]) q = as_quaternion(sample_track(*k, t, snap));
        if (const KeyTrack* k = track_of_[3 * i + 2]) sc = sample_track(*k, t, snap).head<3>();
      }
      Eigen::Affine3d local = Eigen::Affine3d::Identity();
      local.translate(tr);
      local.rotate(q.normalized());
      local.scale(sc);
      global_[i] = node.parent >= 0 && needed_[node.parent] ? global_[node.parent] * local : local;
    }
    for (int j = 0; j < joints(); ++j) {
      const Eigen::Affine3d& g = global_[order_[j]];
      rot_[j] = rotation_part(g.linear());
      pos_[j] = g.translation();
    }
  }
  // Joint j's offset from its parent joint in the parent's frame, at the last pose.
  Eigen::Vector3d local_offset(int j) const {
    return Eigen::Vector3d(rot_[parent_joint_[j]].transpose() * (pos_[j] - pos_[parent_joint_[j]]));
  }
  // A node's mean world scale at the last pose.
  double world_scale(int node) const {
    const Eigen::Matrix3d& m = global_[node].linear();
    return (m.col(0).norm() + m.col(1).norm() + m.col(2).norm()) / 3.0;
  }

 private:
  const AnimatedScene& scene_;
  const std::vector<int>& order_;  // joint index -> node
  std::vector<int> joint_of_, parent_joint_;
  std::vector<char> needed_;
  std::vector<const KeyTrack*> track_of_;  // per node: translation, rotation, scale
  std::vector<Eigen::Affine3d> global_;
  std::vector<Eigen::Matrix3d> rot_;
  std::vector<Eigen::Vector3d> pos_;
};

// Where and how often a take is sampled.
struct TakeFrames {
  double first = 0.0;  // the first key's time, s
  double fps = 0.0;
  Eigen::Index frames = 0;
};

// The take's first key, its rate (options.fps, else the take's own) and its frames. Throws
// InputError on a rate that is not a positive number, too many frames, or frames of `joints`
// joints that need more memory than options.max_bytes.
TakeFrames take_frames(const AnimatedScene& scene, int take, const SceneClipOptions& options, int joints) {
  const SceneTake& st = scene.takes[take];
  TakeFrames out;
  double first = std::numeric_limits<double>::infinity(), last = -first;
  for (const KeyTrack& t : st.tracks) {
    first = std::min(first, t.times.front());
    last = std::max(last, t.times.back());
  }
  const double fps = options.fps > 0 ? options.fps : default_take_rate(scene, take);
  if (!(fps > 0) || !std::isfinite(fps)) throw InputError(scene.source + ": the frame rate is not a positive number");
  const double span = (last - first) * fps;
  if (!std::isfinite(span) || span + 1 > kMaxFrames)
    throw InputError(take_label(scene, take) + " lasts " + std::to_string(last - first) +
                     " s, too long to sample at " + std::to_string(fps) + " fps");
  // Key times are often float32 (glTF, assimp's FBX rate): the last key may fall a hair short of
  // a whole frame (15.6666665 s at 30 fps is frame 469.99999): it still counts as that frame.
  const Eigen::Index frames = static_cast<Eigen::Index>(std::floor(span + kFrameTolerance)) + 1;
  // Channels: root 6, others 3 (+3 where the offset moves): the motion takes at most
  // frames x joints x 6 doubles.
  const double need = static_cast<double>(frames) * joints * 6 * sizeof(double);
  if (need > static_cast<double>(options.max_bytes))
    throw InputError(take_label(scene, take) + ": " + std::to_string(frames) + " frames of " +
                     std::to_string(joints) + " joints need " + describe_bytes(static_cast<size_t>(need)) +
                     ", more than the limit of " + describe_bytes(options.max_bytes) +
                     " (MOSTYLE_MAX_MEMORY_MB)");
  out.first = first;
  out.fps = fps;
  out.frames = frames;
  return out;
}

// The rest pose: offsets and rotations in the parent's frame, the same for every take, and the
// skeleton's size (its longest offset, 1 when it has none).
struct RestPose {
  std::vector<Eigen::Vector3d> offset;
  std::vector<Eigen::Matrix3d> rotation;
  double size = 0.0;
};

RestPose rest_pose(SkeletonPoser& poser) {
  const int joints = poser.joints();
  poser.pose(0.0, 0.0, true);
  RestPose rest;
  rest.offset.assign(joints, Eigen::Vector3d::Zero());
  rest.rotation.resize(joints);
  for (int j = 0; j < joints; ++j) {
    const int parent = poser.parent_joint(j);
    rest.rotation[j] = j == 0 ? poser.rotation(0)
                              : Eigen::Matrix3d(poser.rotation(parent).transpose() * poser.rotation(j));
    if (j == 0) continue;
    rest.offset[j] = poser.local_offset(j);
    rest.size = std::max(rest.size, rest.offset[j].norm());
  }
  if (!(rest.size > 0)) rest.size = 1;
  return rest;
}

// Joints whose offsets leave the rest in any take (the root always): they keep position
// channels, so every take of the file has the same channels. The poser at rest.
std::vector<char> moving_joints(const AnimatedScene& scene, const SkeletonPoser& poser, double size) {
  const int n = static_cast<int>(scene.nodes.size());
  const int joints = poser.joints();
  std::vector<char> moving(joints, 0);
  moving[0] = 1;
  for (const SceneTake& other : scene.takes) {
    for (const KeyTrack& t : other.tracks) {
      if (t.node < 0 || t.node >= n || !poser.needed(t.node)) continue;
      const int j = poser.joint_of(t.node);
      if (t.target == TrackTarget::kTranslation && j > 0) {
        if (!moving[j] && translation_moves(t, scene.nodes[t.node],
                                            poser.world_scale(poser.node(poser.parent_joint(j))),
                                            kRestTolerance * size))
          moving[j] = 1;
      } else if (t.target == TrackTarget::kScale && scale_moves(t, scene.nodes[t.node])) {
        // Every joint below the scaled node (all of them for a node above the root).
        for (int k = 1; k < joints; ++k) {
          if (j < 0) {
            moving[k] = 1;
            continue;
          }
          for (int up = poser.parent_joint(k); up >= 0; up = poser.parent_joint(up))
            if (up == j) moving[k] = 1;
        }
      }
    }
  }
  return moving;
}

// The skeleton's End Sites: leaves no take of the file keys whose offsets stay at rest.
std::vector<char> end_sites(const AnimatedScene& scene, const SkeletonPoser& poser, const std::vector<char>& moving) {
  const int joints = poser.joints();
  std::vector<char> end(joints, 1);
  end[0] = 0;  // the root has channels, even alone
  for (int j = 1; j < joints; ++j)
    if (moving[j]) end[j] = 0;
  for (int j = 1; j < joints; ++j) end[poser.parent_joint(j)] = 0;
  for (const SceneTake& take : scene.takes)
    for (const KeyTrack& t : take.tracks)
      if (t.node >= 0 && t.node < static_cast<int>(scene.nodes.size()) && poser.needed(t.node) &&
          poser.joint_of(t.node) >= 0)
        end[poser.joint_of(t.node)] = 0;
  return end;
}

// The clip's skeleton: the rest pose, ZXY rotations, and positions where the joint moves; End
// Sites without channels.
Skeleton clip_skeleton(const AnimatedScene& scene, const SkeletonPoser& poser, const RestPose& rest,
                       const std::vector<char>& moving, const std::vector<char>& end_site) {
  Skeleton sk;
  sk.metres_per_unit = scene.metres_per_unit;
  for (int j = 0; j < poser.joints(); ++j) {
    Joint joint;
    joint.name = scene.nodes[poser.node(j)].name;
    joint.parent = poser.parent_joint(j);
    joint.offset = rest.offset[j];
    joint.rest_rotation = rest.rotation[j];
    joint.first_channel = sk.channel_count;
    if (end_site[j]) {
      joint.end_site = true;
      sk.joints.push_back(std::move(joint));
      continue;
    }
    if (moving[j]) joint.channels = {Channel::kXposition, Channel::kYposition, Channel::kZposition};
    joint.channels.insert(joint.channels.end(), {Channel::kZrotation, Channel::kXrotation, Channel::kYrotation});
    sk.channel_count += static_cast<int>(joint.channels.size());
    sk.joints.push_back(std::move(joint));
  }
  return sk;
}

// The take's frames into motion (frames x the skeleton's channels): positions, and rotations
// in the parent's frame as Euler angles each near the frame before's.
void write_frames(SkeletonPoser& poser, const Skeleton& sk, const std::vector<char>& moving, const TakeFrames& at,
                  MotionMatrix& motion) {
  const int joints = poser.joints();
  const double snap = kFrameTolerance / at.fps;
  motion.resize(at.frames, sk.channel_count);
  std::vector<Eigen::Vector3d> previous(joints, Eigen::Vector3d::Zero());
  for (Eigen::Index f = 0; f < at.frames; ++f) {
    poser.pose(at.first + static_cast<double>(f) / at.fps, snap, false);
    for (int j = 0; j < joints; ++j) {
      const Joint& joint = sk.joints[j];
      if (joint.end_site) continue;
      int c = joint.first_channel;
      Eigen::Matrix3d local = poser.rotation(j);
      if (joint.parent >= 0) {
        local = poser.rotation(joint.parent).transpose() * poser.rotation(j);
        if (moving[j]) {
          const Eigen::Vector3d o = poser.local_offset(j);
          for (int d = 0; d < 3; ++d) motion(f, c++) = o(d);
        }
      } else {
        for (int d = 0; d < 3; ++d) motion(f, c++) = poser.position(j)(d);
      }
      const Eigen::Vector3d angles = f == 0 ? matrix_to_euler(EulerOrder::kZXY, local)
                                            : matrix_to_euler_near(EulerOrder::kZXY, local, previous[j]);
      previous[j] = angles;
      for (int d = 0; d < 3; ++d) motion(f, c++) = angles(d);
    }
  }
}

}  // namespace

Clip scene_take_to_clip(const AnimatedScene& scene, int take, const SceneClipOptions& options) {
  if (take < 0 || take >= static_cast<int>(scene.takes.size()))
    throw InputError(scene.source + ": has no animation " + std::to_string(take + 1));
  const SceneTake& st = scene.takes[take];
  for (const KeyTrack& t : st.tracks) check_track(scene, take, t);
  if (st.tracks.empty()) throw InputError(take_label(scene, take) + " keys no node: no skeleton moves in it");
  const SceneSkeleton skeleton = scene_skeleton(scene, take);
  SkeletonPoser poser(scene, take, skeleton);
  const TakeFrames at = take_frames(scene, take, options, poser.joints());
  const RestPose rest = rest_pose(poser);
  const std::vector<char> moving = moving_joints(scene, poser, rest.size);
  Clip clip;
  clip.source = scene.source;
  clip.frame_time = 1.0 / at.fps;
  clip.skeleton = clip_skeleton(scene, poser, rest, moving, end_sites(scene, poser, moving));
  write_frames(poser, clip.skeleton, moving, at, clip.motion);
  return clip;
}

}  // namespace mostyle
