#pragma once
// Skeletons of the common conventions built in code, for the major-skeleton and pipeline tests:
// names and hierarchy as the conventions have them, offsets of a plausible human in cm (Y up,
// facing +Z, left = +X), so the zero-length-bone rule and FK have something real to work on.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "engine/base/clip.h"

namespace mostyle::test {

class SkeletonBuilder {
 public:
  // The root gets 6 channels (position + ZXY rotation), other joints 3 rotation channels.
  SkeletonBuilder& joint(const std::string& name, const std::string& parent, double x, double y,
                         double z) {
    Joint j;
    j.name = name;
    j.parent = parent.empty() ? -1 : skeleton_.find(parent);
    j.offset = Eigen::Vector3d(x, y, z);
    if (j.parent < 0) {
      j.channels = {Channel::kXposition, Channel::kYposition, Channel::kZposition,
                    Channel::kZrotation, Channel::kXrotation, Channel::kYrotation};
    } else {
      j.channels = {Channel::kZrotation, Channel::kXrotation, Channel::kYrotation};
    }
    j.first_channel = skeleton_.channel_count;
    skeleton_.channel_count += static_cast<int>(j.channels.size());
    skeleton_.joints.push_back(j);
    return *this;
  }
  // An End Site below `parent`.
  SkeletonBuilder& end(const std::string& parent, double x, double y, double z) {
    Joint j;
    j.name = parent + " End Site";
    j.parent = skeleton_.find(parent);
    j.offset = Eigen::Vector3d(x, y, z);
    j.end_site = true;
    j.first_channel = skeleton_.channel_count;
    skeleton_.joints.push_back(j);
    return *this;
  }
  const Skeleton& skeleton() const { return skeleton_; }

 private:
  Skeleton skeleton_;
};

// A clip of `frames` frames on `skeleton`, all rotations zero, the root at its OFFSET and moving
// along +Z at `speed` units per frame.
inline Clip still_clip(const Skeleton& skeleton, int frames, double speed, double fps = 30.0) {
  Clip clip;
  clip.source = "synthetic.bvh";
  clip.skeleton = skeleton;
  clip.frame_time = 1.0 / fps;
  clip.motion = MotionMatrix::Zero(frames, skeleton.channel_count);
  const Joint& root = skeleton.joints[0];
  for (int f = 0; f < frames; ++f) {
    clip.motion(f, 0) = root.offset.x();
    clip.motion(f, 1) = root.offset.y();
    clip.motion(f, 2) = root.offset.z() + speed * f;
  }
  return clip;
}

// Retargeted CMU (the cmu142_* files): zero-length LHipJoint, LowerBack, LeftShoulder,
// LeftFingerBase, LThumb and their right twins.
inline Skeleton cmu_retargeted_skeleton() {
  SkeletonBuilder b;
  b.joint("Hips", "", 0, 95, 0);
  for (const char* side : {"Left", "Right"}) {
    const std::string s = side;
    const double sign = s == "Left" ? 1 : -1;
    const std::string l = s.substr(0, 1);
    b.joint(l + "HipJoint", "Hips", 0, 0, 0)
        .joint(s + "UpLeg", l + "HipJoint", sign * 9, -5, 0)
        .joint(s + "Leg", s + "UpLeg", 0, -42, 0)
        .joint(s + "Foot", s + "Leg", 0, -42, 0)
        .joint(s + "ToeBase", s + "Foot", 0, -6, 13)
        .end(s + "ToeBase", 0, 0, 0);
  }
  b.joint("LowerBack", "Hips", 0, 0, 0)
      .joint("Spine", "LowerBack", 0, 12, 0)
      .joint("Spine1", "Spine", 0, 12, 0)
      .joint("Neck", "Spine1", 0, 0, 0)
      .joint("Neck1", "Neck", 0, 10, 0)
      .joint("Head", "Neck1", 0, 10, 0)
      .end("Head", 0, 0, 0);
  for (const char* side : {"Left", "Right"}) {
    const std::string s = side;
    const double sign = s == "Left" ? 1 : -1;
    b.joint(s + "Shoulder", "Spine1", 0, 0, 0)
        .joint(s + "Arm", s + "Shoulder", sign * 18, 5, 0)
        .joint(s + "ForeArm", s + "Arm", sign * 28, 0, 0)
        .joint(s + "Hand", s + "ForeArm", sign * 25, 0, 0)
        .joint(s + "FingerBase", s + "Hand", 0, 0, 0)
        .joint(s + "HandIndex1", s + "FingerBase", sign * 4, 0, 0)
        .end(s + "HandIndex1", 0, 0, 0)
        .joint(std::string(1, s[0]) + "Thumb", s + "Hand", 0, 0, 0)
        .end(std::string(1, s[0]) + "Thumb", 0, 0, 0);
  }
  return b.skeleton();
}

// Bandai Namco: a static dummy ROOT joint_Root, the trajectory on Hips, clavicles Shoulder_L/R,
// no fingers. (The real files' bones point along local +X; the names are what matters here.)
inline Skeleton bandai_skeleton() {
  SkeletonBuilder b;
  b.joint("joint_Root", "", 0, 0, 0)
      .joint("Hips", "joint_Root", 0, 94, -3)
      .joint("Spine", "Hips", 0, 16, 0)
      .joint("Chest", "Spine", 0, 9, 0)
      .joint("Neck", "Chest", 0, 16, 0)
      .joint("Head", "Neck", 0, 6, 0)
      .end("Head", 0, 0, 0);
  for (const char* side : {"L", "R"}) {
    const std::string s = side;
    const double sign = s == "L" ? 1 : -1;
    b.joint("Shoulder_" + s, "Chest", sign * 5, 13, 0)
        .joint("UpperArm_" + s, "Shoulder_" + s, sign * 5, 0, 0)
        .joint("LowerArm_" + s, "UpperArm_" + s, sign * 24, 0, 0)
        .joint("Hand_" + s, "LowerArm_" + s, sign * 22, 0, 0)
        .end("Hand_" + s, 0, 0, 0);
  }
  for (const char* side : {"L", "R"}) {
    const std::string s = side;
    const double sign = s == "L" ? 1 : -1;
    b.joint("UpperLeg_" + s, "Hips", sign * 6.5, -2, 0)
        .joint("LowerLeg_" + s, "UpperLeg_" + s, 0, -39, 0)
        .joint("Foot_" + s, "LowerLeg_" + s, 0, -41, 0)
        .joint("Toes_" + s, "Foot_" + s, 0, -5, 11)
        .end("Toes_" + s, 0, 0, 0);
  }
  return b.skeleton();
}

// Mixamo: "mixamorig:" names, three spine joints, clavicles LeftShoulder, five fingers.
inline Skeleton mixamo_skeleton() {
  SkeletonBuilder b;
  b.joint("mixamorig:Hips", "", 0, 100, 0)
      .joint("mixamorig:Spine", "mixamorig:Hips", 0, 10, 0)
      .joint("mixamorig:Spine1", "mixamorig:Spine", 0, 12, 0)
      .joint("mixamorig:Spine2", "mixamorig:Spine1", 0, 13, 0)
      .joint("mixamorig:Neck", "mixamorig:Spine2", 0, 15, 0)
      .joint("mixamorig:Head", "mixamorig:Neck", 0, 9, 0)
      .joint("mixamorig:HeadTop_End", "mixamorig:Head", 0, 18, 0)
      .end("mixamorig:HeadTop_End", 0, 0, 0);
  for (const char* side : {"Left", "Right"}) {
    const std::string s = std::string("mixamorig:") + side;
    const double sign = std::string(side) == "Left" ? 1 : -1;
    b.joint(s + "Shoulder", "mixamorig:Spine2", sign * 6, 12, 0)
        .joint(s + "Arm", s + "Shoulder", sign * 12, 0, 0)
        .joint(s + "ForeArm", s + "Arm", sign * 27, 0, 0)
        .joint(s + "Hand", s + "ForeArm", sign * 25, 0, 0);
    for (const char* finger : {"Thumb", "Index", "Middle", "Ring", "Pinky"}) {
      b.joint(s + "Hand" + finger + "1", s + "Hand", sign * 4, 0, 0)
          .joint(s + "Hand" + finger + "2", s + "Hand" + finger + "1", sign * 3, 0, 0)
          .end(s + "Hand" + finger + "2", sign * 2, 0, 0);
    }
  }
  for (const char* side : {"Left", "Right"}) {
    const std::string s = std::string("mixamorig:") + side;
    const double sign = std::string(side) == "Left" ? 1 : -1;
    b.joint(s + "UpLeg", "mixamorig:Hips", sign * 9, -6, 0)
        .joint(s + "Leg", s + "UpLeg", 0, -43, 0)
        .joint(s + "Foot", s + "Leg", 0, -42, 0)
        .joint(s + "ToeBase", s + "Foot", 0, -7, 12)
        .joint(s + "Toe_End", s + "ToeBase", 0, 0, 6)
        .end(s + "Toe_End", 0, 0, 0);
  }
  return b.skeleton();
}

// 3ds Max Biped: the trajectory node Bip01, Bip01 Pelvis at the same place, thighs below the
// spine, clavicles, Finger0 (thumb) and Finger1, Toe0 with its Nub.
inline Skeleton biped_skeleton() {
  SkeletonBuilder b;
  b.joint("Bip01", "", 0, 98, 0)
      .joint("Bip01 Pelvis", "Bip01", 0, 0, 0)
      .joint("Bip01 Spine", "Bip01 Pelvis", 0, 8, 0)
      .joint("Bip01 Spine1", "Bip01 Spine", 0, 20, 0)
      .joint("Bip01 Neck", "Bip01 Spine1", 0, 18, 0)
      .joint("Bip01 Head", "Bip01 Neck", 0, 8, 0)
      .joint("Bip01 HeadNub", "Bip01 Head", 0, 20, 0)
      .end("Bip01 HeadNub", 0, 0, 0);
  for (const char* side : {"L", "R"}) {
    const std::string s = std::string("Bip01 ") + side + " ";
    const double sign = std::string(side) == "L" ? 1 : -1;
    b.joint(s + "Thigh", "Bip01 Spine", sign * 9, -13, 0)
        .joint(s + "Calf", s + "Thigh", 0, -42, 0)
        .joint(s + "Foot", s + "Calf", 0, -42, 0)
        .joint(s + "Toe0", s + "Foot", 0, -7, 12)
        .joint(s + "Toe0Nub", s + "Toe0", 0, 0, 5)
        .end(s + "Toe0Nub", 0, 0, 0);
    b.joint(s + "Clavicle", "Bip01 Neck", sign * 3, 0, 0)
        .joint(s + "UpperArm", s + "Clavicle", sign * 15, 0, 0)
        .joint(s + "Forearm", s + "UpperArm", sign * 27, 0, 0)
        .joint(s + "Hand", s + "Forearm", sign * 25, 0, 0)
        .joint(s + "Finger0", s + "Hand", sign * 2, 0, 3)
        .joint(s + "Finger1", s + "Hand", sign * 8, 0, 0)
        .end(s + "Finger1", sign * 3, 0, 0);
  }
  return b.skeleton();
}

// CMU in 3ds Max/Poser naming (hip, abdomen, chest, lCollar, lShldr, lButtock, lThigh, lShin,
// lFoot), no toes and no fingers.
inline Skeleton cmu_poser_skeleton() {
  SkeletonBuilder b;
  b.joint("hip", "", 0, 95, 0)
      .joint("abdomen", "hip", 0, 10, 0)
      .joint("chest", "abdomen", 0, 15, 0)
      .joint("neck", "chest", 0, 20, 0)
      .joint("head", "neck", 0, 8, 0)
      .end("head", 0, 15, 0);
  for (const char* side : {"l", "r"}) {
    const std::string s = side;
    const double sign = s == "l" ? 1 : -1;
    b.joint(s + "Collar", "chest", sign * 3, 15, 0)
        .joint(s + "Shldr", s + "Collar", sign * 15, 0, 0)
        .joint(s + "ForeArm", s + "Shldr", sign * 28, 0, 0)
        .joint(s + "Hand", s + "ForeArm", sign * 25, 0, 0)
        .end(s + "Hand", sign * 8, 0, 0);
    b.joint(s + "Buttock", "hip", sign * 5, -3, 0)
        .joint(s + "Thigh", s + "Buttock", sign * 4, -3, 0)
        .joint(s + "Shin", s + "Thigh", 0, -42, 0)
        .joint(s + "Foot", s + "Shin", 0, -42, 0)
        .end(s + "Foot", 0, -6, 13);
  }
  return b.skeleton();
}

// Kinect v1's 20 joints (the canonical set's model): HipCenter .. FootLeft.
inline Skeleton kinect_skeleton() {
  SkeletonBuilder b;
  b.joint("HipCenter", "", 0, 95, 0)
      .joint("Spine", "HipCenter", 0, 10, 0)
      .joint("ShoulderCenter", "Spine", 0, 35, 0)
      .joint("Head", "ShoulderCenter", 0, 20, 0);
  for (const char* side : {"Left", "Right"}) {
    const std::string s = side;
    const double sign = s == "Left" ? 1 : -1;
    b.joint("Shoulder" + s, "ShoulderCenter", sign * 18, -3, 0)
        .joint("Elbow" + s, "Shoulder" + s, sign * 28, 0, 0)
        .joint("Wrist" + s, "Elbow" + s, sign * 25, 0, 0)
        .joint("Hand" + s, "Wrist" + s, sign * 8, 0, 0);
  }
  for (const char* side : {"Left", "Right"}) {
    const std::string s = side;
    const double sign = s == "Left" ? 1 : -1;
    b.joint("Hip" + s, "HipCenter", sign * 9, -5, 0)
        .joint("Knee" + s, "Hip" + s, 0, -42, 0)
        .joint("Ankle" + s, "Knee" + s, 0, -42, 0)
        .joint("Foot" + s, "Ankle" + s, 0, -6, 12);
  }
  return b.skeleton();
}

// A bare rig without toes or hand joints: Hips, Spine, Chest, Head, arms ending at the wrist
// (LeftHand with an End Site), legs ending at the ankle (LeftFoot with an End Site).
inline Skeleton no_toes_no_hands_skeleton() {
  SkeletonBuilder b;
  b.joint("Hips", "", 0, 95, 0)
      .joint("Spine", "Hips", 0, 12, 0)
      .joint("Chest", "Spine", 0, 15, 0)
      .joint("Head", "Chest", 0, 25, 0)
      .end("Head", 0, 15, 0);
  for (const char* side : {"Left", "Right"}) {
    const std::string s = side;
    const double sign = s == "Left" ? 1 : -1;
    b.joint(s + "Arm", "Chest", sign * 18, 15, 0)
        .joint(s + "ForeArm", s + "Arm", sign * 28, 0, 0)
        .joint(s + "Hand", s + "ForeArm", sign * 25, 0, 0)
        .end(s + "Hand", sign * 8, 0, 0);
    b.joint(s + "UpLeg", "Hips", sign * 9, -5, 0)
        .joint(s + "Leg", s + "UpLeg", 0, -42, 0)
        .joint(s + "Foot", s + "Leg", 0, -42, 0)
        .end(s + "Foot", 0, -6, 13);
  }
  return b.skeleton();
}

}  // namespace mostyle::test
