#include "engine/io/scene_animation.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/io/error.h"
#include "engine/kinematics/euler.h"

namespace mostyle {
namespace {

// Relative change of a joint's offset (to the skeleton's size) that still counts as one value:
// float32 key values composed down a chain differ by about 1e-6.
constexpr double kOffsetTolerance = 1e-5;
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
  std::vector<TakeInfo> out;
  for (const SceneTake& take : scene.takes) {
    TakeInfo info;
    info.name = take.name;
    double first = std::numeric_limits<double>::infinity(), last = -first;
    for (const KeyTrack& t : take.tracks) {
      if (t.times.empty()) continue;
      first = std::min(first, t.times.front());
      last = std::max(last, t.times.back());
      info.keys = std::max(info.keys, static_cast<int>(t.times.size()));
    }
    info.seconds = last >= first && std::isfinite(last - first) ? last - first : 0.0;
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

Clip scene_take_to_clip(const AnimatedScene& scene, int take, const SceneClipOptions& options) {
  if (take < 0 || take >= static_cast<int>(scene.takes.size()))
    throw InputError(scene.source + ": has no animation " + std::to_string(take + 1));
  const SceneTake& st = scene.takes[take];
  const int n = static_cast<int>(scene.nodes.size());
  for (const KeyTrack& t : st.tracks) check_track(scene, take, t);
  if (st.tracks.empty()) throw InputError(take_label(scene, take) + " keys no node: no skeleton moves in it");

  // The skeleton: keyed nodes, rooted at their lowest common ancestor, and the nodes between.
  std::vector<char> keyed(n, 0);
  for (const KeyTrack& t : st.tracks) keyed[t.node] = 1;
  std::vector<int> depth(n, 0);
  for (int i = 0; i < n; ++i) {
    if (scene.nodes[i].parent >= i)
      throw InputError(scene.source + ": node '" + scene.nodes[i].name + "' comes before its parent");
    depth[i] = scene.nodes[i].parent < 0 ? 0 : depth[scene.nodes[i].parent] + 1;
  }
  int root = -1;
  for (int i = 0; i < n; ++i) {
    if (!keyed[i]) continue;
    if (root < 0) {
      root = i;
      continue;
    }
    int a = root, b = i;
    while (a != b && a >= 0 && b >= 0) {
      if (depth[a] >= depth[b]) a = scene.nodes[a].parent;
      else b = scene.nodes[b].parent;
    }
    root = a == b ? a : -1;
    if (root < 0) break;
  }
  // The scene root that holds everything (assimp's) is no skeleton's root unless it moves itself.
  if (root < 0 || (root == scene.scene_root && !keyed[root])) {
    std::vector<std::string> tops;
    for (int i = 0; i < n && tops.size() < 3; ++i) {
      if (!keyed[i]) continue;
      int up = scene.nodes[i].parent;
      while (up >= 0 && !keyed[up]) up = scene.nodes[up].parent;
      if (up < 0) tops.push_back("'" + scene.nodes[i].name + "'");
    }
    std::string list;
    for (size_t i = 0; i < tops.size(); ++i) list += (i ? ", " : "") + tops[i];
    throw InputError(take_label(scene, take) + " moves several skeletons (rooted at " + list +
                     "): keep one per file");
  }
  std::vector<char> in_skeleton(n, 0);
  for (int i = 0; i < n; ++i) {
    if (!keyed[i]) continue;
    for (int up = i; up >= 0 && !in_skeleton[up]; up = scene.nodes[up].parent) {
      in_skeleton[up] = 1;
      if (up == root) break;
    }
  }
  // Nodes whose transforms matter: the skeleton and everything above its root.
  std::vector<char> needed = in_skeleton;
  for (int up = scene.nodes[root].parent; up >= 0; up = scene.nodes[up].parent) needed[up] = 1;

  // Joints in depth-first order (parents first, siblings in file order).
  std::vector<std::vector<int>> children(n);
  for (int i = 0; i < n; ++i)
    if (in_skeleton[i] && i != root) children[scene.nodes[i].parent].push_back(i);
  std::vector<int> order;  // joint index -> node
  std::vector<int> joint_of(n, -1);
  {
    std::vector<int> stack{root};
    while (!stack.empty()) {
      const int node = stack.back();
      stack.pop_back();
      joint_of[node] = static_cast<int>(order.size());
      order.push_back(node);
      for (auto it = children[node].rbegin(); it != children[node].rend(); ++it) stack.push_back(*it);
    }
  }
  const int joints = static_cast<int>(order.size());

  // Sampling times.
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

  // Channels: root 6, others 3 (+3 where the offset changes, decided after sampling): the
  // motion takes at most frames x joints x 6 doubles.
  const double need = static_cast<double>(frames) * joints * 6 * sizeof(double);
  if (need > static_cast<double>(options.max_bytes))
    throw InputError(take_label(scene, take) + ": " + std::to_string(frames) + " frames of " +
                     std::to_string(joints) + " joints need " + describe_bytes(static_cast<size_t>(need)) +
                     ", more than the limit of " + describe_bytes(options.max_bytes) +
                     " (MOSTYLE_MAX_MEMORY_MB)");

  // Tracks per node.
  std::vector<const KeyTrack*> track_of(3 * static_cast<size_t>(n), nullptr);
  for (const KeyTrack& t : st.tracks) track_of[3 * t.node + static_cast<int>(t.target)] = &t;

  // World rotations (orthonormal) and positions of the joints at one frame. Computed twice per
  // frame (once to find the joints whose offsets change, once to write the channels) rather than
  // kept for all frames: that store took more memory than the clip and its page faults most of
  // the time on a 20 MB file.
  std::vector<Eigen::Affine3d> global(n, Eigen::Affine3d::Identity());
  std::vector<Eigen::Matrix3d> rot(joints);
  std::vector<Eigen::Vector3d> pos(joints);
  const double snap = kFrameTolerance / fps;
  const auto world_pose = [&](Eigen::Index f) {
    const double t = first + static_cast<double>(f) / fps;
    for (int i = 0; i < n; ++i) {
      if (!needed[i]) continue;
      const SceneNode& node = scene.nodes[i];
      Eigen::Vector3d tr = node.translation, sc = node.scale;
      Eigen::Quaterniond q = node.rotation;
      if (const KeyTrack* k = track_of[3 * i]) tr = sample_track(*k, t, snap).head<3>();
      if (const KeyTrack* k = track_of[3 * i + 1]) q = as_quaternion(sample_track(*k, t, snap));
      if (const KeyTrack* k = track_of[3 * i + 2]) sc = sample_track(*k, t, snap).head<3>();
      Eigen::Affine3d local = Eigen::Affine3d::Identity();
      local.translate(tr);
      local.rotate(q.normalized());
      local.scale(sc);
      global[i] = node.parent >= 0 && needed[node.parent] ? global[node.parent] * local : local;
    }
    for (int j = 0; j < joints; ++j) {
      const Eigen::Affine3d& g = global[order[j]];
      rot[j] = rotation_part(g.linear());
      pos[j] = g.translation();
    }
  };
  std::vector<int> parent_joint(joints, -1);
  for (int j = 1; j < joints; ++j) parent_joint[j] = joint_of[scene.nodes[order[j]].parent];
  const auto local_offset = [&](int j) {
    return Eigen::Vector3d(rot[parent_joint[j]].transpose() * (pos[j] - pos[parent_joint[j]]));
  };

  // Offsets in the parent's frame at frame 0, and which joints need position channels.
  std::vector<Eigen::Vector3d> offset(joints, Eigen::Vector3d::Zero());
  world_pose(0);
  double size = 0;
  for (int j = 1; j < joints; ++j) {
    offset[j] = local_offset(j);
    size = std::max(size, offset[j].norm());
  }
  if (!(size > 0)) size = 1;
  std::vector<char> moving(joints, 0);
  moving[0] = 1;
  for (Eigen::Index f = 1; f < frames; ++f) {
    world_pose(f);
    for (int j = 1; j < joints; ++j)
      if (!moving[j] && (local_offset(j) - offset[j]).norm() > kOffsetTolerance * size) moving[j] = 1;
  }

  Clip clip;
  clip.source = scene.source;
  clip.frame_time = 1.0 / fps;
  Skeleton& sk = clip.skeleton;
  for (int j = 0; j < joints; ++j) {
    Joint joint;
    joint.name = scene.nodes[order[j]].name;
    joint.parent = parent_joint[j];
    joint.offset = j == 0 ? Eigen::Vector3d::Zero() : offset[j];
    joint.first_channel = sk.channel_count;
    if (moving[j]) joint.channels = {Channel::kXposition, Channel::kYposition, Channel::kZposition};
    joint.channels.insert(joint.channels.end(), {Channel::kZrotation, Channel::kXrotation, Channel::kYrotation});
    sk.channel_count += static_cast<int>(joint.channels.size());
    sk.joints.push_back(std::move(joint));
  }
  clip.motion.resize(frames, sk.channel_count);
  std::vector<Eigen::Vector3d> previous(joints, Eigen::Vector3d::Zero());
  for (Eigen::Index f = 0; f < frames; ++f) {
    world_pose(f);
    for (int j = 0; j < joints; ++j) {
      const Joint& joint = sk.joints[j];
      int c = joint.first_channel;
      Eigen::Matrix3d local = rot[j];
      if (joint.parent >= 0) {
        local = rot[joint.parent].transpose() * rot[j];
        if (moving[j]) {
          const Eigen::Vector3d o = local_offset(j);
          for (int d = 0; d < 3; ++d) clip.motion(f, c++) = o(d);
        }
      } else {
        for (int d = 0; d < 3; ++d) clip.motion(f, c++) = pos[j](d);
      }
      const Eigen::Vector3d angles = f == 0 ? matrix_to_euler(EulerOrder::kZXY, local)
                                            : matrix_to_euler_near(EulerOrder::kZXY, local, previous[j]);
      previous[j] = angles;
      for (int d = 0; d < 3; ++d) clip.motion(f, c++) = angles(d);
    }
  }
  return clip;
}

}  // namespace mostyle
