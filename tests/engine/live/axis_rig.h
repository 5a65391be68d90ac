#pragma once
// A 59-joint skeleton laid out as Axis Neuron's BVH broadcasting sends it (hips, legs without
// toes, four spine joints, neck, head, shoulders, arms, and hands with five fingers of three
// joints each and an in-hand joint for four of them; centimetres, Y up, rotations Y X Z, the root
// with position channels), and a take's walk put on it: the take's major-joint positions, scaled
// by the legs, solved into the rig's rotations (export_solve.h), the fingers left at rest. For
// the live styler's tests and benchmark: a stream on a rig no take has.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "engine/export/export_solve.h"
#include "engine/io/bvh/bvh_read.h"
#include "engine/base/clip.h"
#include "engine/kinematics/kinematics.h"
#include "engine/kinematics/limb_length.h"
#include "engine/prepare/major_skeleton.h"
#include "engine/prepare/major_take.h"
#include "engine/prepare/retarget.h"

namespace mostyle::test {

inline std::string axis_joint(const std::string& name, double x, double y, double z, const std::string& body,
                              const std::string& indent) {
  return indent + "JOINT " + name + "\n" + indent + "{\n" + indent + "  OFFSET " + std::to_string(x) + " " +
         std::to_string(y) + " " + std::to_string(z) + "\n" + indent + "  CHANNELS 3 Yrotation Xrotation Zrotation\n" +
         body + indent + "}\n";
}

inline std::string axis_end(double x, double y, double z, const std::string& indent) {
  return indent + "End Site\n" + indent + "{\n" + indent + "  OFFSET " + std::to_string(x) + " " + std::to_string(y) +
         " " + std::to_string(z) + "\n" + indent + "}\n";
}

// A chain of joints, each `step` from the one before along x (side: -1 right, +1 left), ending
// in an End Site.
inline std::string axis_chain(const std::vector<std::string>& names, const Eigen::Vector3d& first, double step,
                              double side, const std::string& indent) {
  std::string body = axis_end(side * step * 0.6, 0, 0, indent + "  ");
  for (size_t i = names.size(); i-- > 0;) {
    const Eigen::Vector3d at = i == 0 ? first : Eigen::Vector3d(side * step, 0, 0);
    body = axis_joint(names[i], at.x(), at.y(), at.z(), body, indent + std::string(2 * i, ' '));
  }
  return body;
}

inline std::string axis_arm(const std::string& side_name, double side) {
  const std::string s = side_name;
  const std::string in = "          ";  // under the hand
  std::string fingers = axis_chain({s + "HandThumb1", s + "HandThumb2", s + "HandThumb3"},
                                   Eigen::Vector3d(side * 2.5, -1.0, 3.0), 3.0, side, in);
  const char* names[] = {"Index", "Middle", "Ring", "Pinky"};
  const double across[] = {2.0, 0.5, -1.0, -2.5};
  for (int f = 0; f < 4; ++f) {
    const std::string n = names[f];
    const std::string chain = axis_chain({s + "Hand" + n + "1", s + "Hand" + n + "2", s + "Hand" + n + "3"},
                                         Eigen::Vector3d(side * 6.0, 0, 0), 3.0, side, in + "  ");
    fingers += axis_joint(s + "InHand" + n, side * 3.0, 0.0, across[f], chain, in);
  }
  const std::string hand = axis_joint(s + "Hand", side * 26.0, 0, 0, fingers, "        ");
  const std::string fore = axis_joint(s + "ForeArm", side * 28.0, 0, 0, hand, "      ");
  const std::string arm = axis_joint(s + "Arm", side * 13.0, 0, 0, fore, "    ");
  return axis_joint(s + "Shoulder", side * 3.0, 8.0, 0, arm, "  ");
}

inline std::string axis_leg(const std::string& s, double side) {
  const std::string foot = axis_joint(s + "Foot", 0, -41.0, 0, axis_end(0, -7.0, 14.0, "      "), "    ");
  const std::string leg = axis_joint(s + "Leg", 0, -42.0, 0, foot, "  ");
  return axis_joint(s + "UpLeg", side * 9.5, 0, 0, leg, "");
}

// The skeleton with no frames (59 joints, 180 values a frame), fps 60.
inline Clip axis_skeleton() {
  std::string head = axis_joint("Head", 0, 9.0, 0, axis_end(0, 15.0, 0, "    "), "  ");
  const std::string neck = axis_joint("Neck", 0, 12.0, 0, head, "");
  std::string top = neck + axis_arm("Right", -1.0) + axis_arm("Left", 1.0);
  std::string spine = axis_joint("Spine3", 0, 10.0, 0, top, "");
  spine = axis_joint("Spine2", 0, 10.0, 0, spine, "");
  spine = axis_joint("Spine1", 0, 10.0, 0, spine, "");
  spine = axis_joint("Spine", 0, 10.0, 0, spine, "");
  const std::string text = "HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0 0\n"
                           "  CHANNELS 6 Xposition Yposition Zposition Yrotation Xrotation Zrotation\n" +
                           axis_leg("Right", -1.0) + axis_leg("Left", 1.0) + spine + "}\nMOTION\nFrames: 0\nFrame Time: 0.0166667\n";
  return parse_bvh(text, "axis_neuron.bvh");
}

// The take's walk on the Axis rig at the take's rate: its major joints' positions scaled by the
// legs and put on the rig's bones, solved into the rig's rotations from its rest pose.
inline Clip on_axis_rig(const Clip& take) {
  Clip rig = axis_skeleton();
  rig.source = "axis_" + take.source;
  rig.frame_time = take.frame_time;
  const MajorMapping rig_map = map_major_joints(rig.skeleton), take_map = map_major_joints(take);
  const std::vector<int> majors = shared_major_joints(rig_map, rig.source, take_map, take.source);
  const std::vector<int> parents = subset_parents(majors);
  std::vector<int> rig_joints;
  for (int m : majors) rig_joints.push_back(rig_map.joint[static_cast<size_t>(m)]);
  const std::vector<Eigen::Vector3d> rest = rest_positions(rig.skeleton);
  Eigen::MatrixXd rest_row(1, 3 * static_cast<Eigen::Index>(majors.size()));
  for (size_t c = 0; c < majors.size(); ++c) rest_row.block<1, 3>(0, 3 * static_cast<Eigen::Index>(c)) = rest[static_cast<size_t>(rig_joints[c])].transpose();
  const std::vector<double> lengths = bone_lengths(rest_row, parents);
  const MajorTake major = extract_major_take(take, take_map, majors, 0.0);
  const std::vector<double> take_lengths = bone_lengths(major.world, parents);
  auto column = [&](MajorJoint j) { return major_column(majors, static_cast<int>(j)); };
  const int leg[6] = {column(MajorJoint::kLeftHip), column(MajorJoint::kLeftKnee), column(MajorJoint::kLeftAnkle),
                      column(MajorJoint::kRightHip), column(MajorJoint::kRightKnee), column(MajorJoint::kRightAnkle)};
  Eigen::MatrixXd world = retarget_positions(major.world, parents, lengths, leg_length(lengths, leg), leg_length(take_lengths, leg));
  adopt_group_shapes(world, rest_row, parents);
  apply_limb_lengths(world, parents, lengths);
  rig.motion = MotionMatrix::Zero(world.rows(), rig.skeleton.channel_count);
  ExportFrameSolver solver(rig.skeleton, rig_joints, rig.source);
  Eigen::VectorXd targets(world.cols());
  const MotionMatrix rest_values = MotionMatrix::Zero(1, rig.skeleton.channel_count);
  for (Eigen::Index f = 0; f < world.rows(); ++f) {
    targets = world.row(f).transpose();
    solver.solve(rest_values.data(), targets.data(), rig.motion.row(f).data());
  }
  return rig;
}

}  // namespace mostyle::test
