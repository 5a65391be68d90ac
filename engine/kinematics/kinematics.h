#pragma once
// Forward kinematics of a clip: global transforms and positions of every joint per frame.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "engine/base/clip.h"

namespace mostyle {

// Local rotation of one joint at one frame from its rotation channels, applied in file order
// (channels "Zrotation Xrotation Yrotation" give Rz * Rx * Ry). values: the frame's row.
Eigen::Matrix3d joint_local_rotation(const Joint& joint, const double* frame_values);

// Local translation, Blender's reading: the OFFSET for a joint without position
// channels; for a joint with any, its position channels replace the whole OFFSET, a missing
// one reading as 0 (Blender and three.js both read it so; three.js then adds the OFFSET).
Eigen::Vector3d joint_local_translation(const Joint& joint, const double* frame_values);

// Global positions of all joints (End Sites included, in skeleton order) at every frame:
// frames x 3*joints, file units and axes. One forward pass per frame (parents come before
// children), so any depth works. O(frames * joints).
Eigen::MatrixXd joint_positions(const Clip& clip);

// Global positions of `joints` only (indices into the skeleton), in that order: frames x
// 3*joints.size(). Only the joints on their chains to the root are posed, each as
// joint_positions poses it (the same values), four frames at a time (AVX2 where the CPU has
// it). O(frames * joints on those chains).
Eigen::MatrixXd joint_positions(const Clip& clip, const std::vector<int>& joints);

// Global positions and rotations of all joints at one frame.
struct Pose {
  std::vector<Eigen::Vector3d> positions;  // per joint, file units
  std::vector<Eigen::Matrix3d> rotations;  // per joint, global
};
Pose pose_at(const Clip& clip, int frame);  // frame in [0, clip.frames())

// One frame's FK, for motion posed a frame at a time as it comes (a stream) or as it is solved:
// every joint's global rotation and position at `values` (the frame's row: skeleton.channel_count
// values) into *pose, resized to the skeleton's joints; the values joint_positions and pose_at
// give. Allocation-free once *pose has its size. O(joints).
void pose_frame(const Skeleton& skeleton, const double* values, Pose* pose);
// The same for the joints of `chain` only (parents first, each joint's parent in it: a set of
// joints and their ancestors), the others' entries in *pose (which holds every joint) left as
// they were. O(chain).
void pose_frame(const Skeleton& skeleton, const double* values, const std::vector<int>& chain, Pose* pose);

// The joints to pose for `joints`: those and their ancestors, each once, parents first (a chain
// for pose_frame). O(joints in the skeleton).
std::vector<int> chain_joints(const Skeleton& skeleton, const std::vector<int>& joints);
// Joint j's global rotation and position into *pose from its local rotation and translation and
// its parent's global ones (posed before it); a root's are its local ones. The step pose_frame
// takes per joint, for a solver that sets each joint's rotation before its children's. O(1).
void place_joint(const Skeleton& skeleton, int j, const Eigen::Matrix3d& local_rotation,
                 const Eigen::Vector3d& local_translation, Pose* pose);

// Rest pose: each joint at its OFFSET turned by its parents' Joint::rest_rotation (identity for
// BVH: all rotation channels zero), position channels taken as the OFFSET: positions per joint,
// file units. O(joints).
std::vector<Eigen::Vector3d> rest_positions(const Skeleton& skeleton);

}  // namespace mostyle
