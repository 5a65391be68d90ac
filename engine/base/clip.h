#pragma once
// A motion clip as a BVH file holds it: a skeleton of joints with channels, and per-frame
// channel values. Value types only; reading and writing live in io/bvh/.
#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

namespace mostyle {

enum class Channel { kXposition, kYposition, kZposition, kXrotation, kYrotation, kZrotation };

inline bool is_rotation(Channel c) { return c >= Channel::kXrotation; }
inline bool is_position(Channel c) { return c <= Channel::kZposition; }
// 0, 1, 2 for X, Y, Z.
inline int channel_axis(Channel c) { return static_cast<int>(c) % 3; }
const char* channel_name(Channel c);  // "Xposition" ...

struct Joint {
  std::string name;          // as in the file; End Sites are named "<parent> End Site"
  int parent = -1;           // index into Skeleton::joints, -1 for a root
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();  // OFFSET, file units
  std::vector<Channel> channels;  // in file order; empty for End Sites
  int first_channel = 0;     // index of this joint's first value in a frame row
  bool end_site = false;     // an "End Site" leaf: no channels, not a real joint
  int line = 0;              // 1-based line of its ROOT/JOINT/End Site keyword, for messages
  // Its rotation in its parent's frame in the file's rest pose: identity for BVH (whose rest
  // pose is every rotation zero); FBX and glTF: the node's own rotation, the root's including
  // the nodes above it. Motion channels replace it; rest_positions (kinematics.h) reads it.
  Eigen::Matrix3d rest_rotation = Eigen::Matrix3d::Identity();
};

// Joints are stored parents before children (file order), so one forward pass does FK.
struct Skeleton {
  std::vector<Joint> joints;
  int channel_count = 0;     // values per frame
  // What one file unit is in metres where the file says it (glTF: 1, its unit being the metre);
  // 0 where it does not (BVH has no unit; FBX as assimp gives it): kinematics/units.h
  // metres_per_unit then guesses it from the skeleton's size.
  double metres_per_unit = 0.0;

  int find(const std::string& name) const;  // index or -1 (End Sites never match)
  int joint_count_without_end_sites() const;
  std::vector<int> children(int joint) const;
};

// Frame rate from a BVH frame time, snapped to a whole number when within 0.05% of it
// (0.008333 s gives 120.005 Hz, which is 120; 0.0333333 gives 30).
double frame_rate_from_frame_time(double frame_time);

// motion: frames x Skeleton::channel_count, angles in degrees, positions in file units.
using MotionMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

struct Clip {
  std::string source;  // file name used in messages
  Skeleton skeleton;
  MotionMatrix motion;
  double frame_time = 1.0 / 30.0;  // seconds, as written in the file

  int frames() const { return static_cast<int>(motion.rows()); }
  double fps() const { return frame_rate_from_frame_time(frame_time); }
};

}  // namespace mostyle
