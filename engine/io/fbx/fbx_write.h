#pragma once
// Writing a clip as binary FBX (7.4 by default, or 7.5): the skeleton as an armature that
// Blender, Maya-style tools and assimp read as one skeleton with one animation. Our own writer
// (fbx_binary.h lays out the bytes): assimp's FBX exporter writes a skeleton without a mesh as
// "Null" models with no time mode of the motion's rate, its key times count seconds as frames,
// and Blender 3.4 cannot open its binary files.
//
// What the file holds:
// - GlobalSettings: Y up, Z front, X right (right-handed), UnitScaleFactor the centimetres per
//   file unit (kinematics/units.h metres_per_unit: the unit the source file states, else the
//   guess from the skeleton's size; 1 when neither tells), TimeMode the motion's rate (an FBX
//   rate when it is one of them, else custom), CustomFrameRate the rate, TimeSpan the frames.
// - Model "Null" named after the take: the armature, parent of the skeleton's roots, with a
//   NodeAttribute "Null".
// - Model "LimbNode" per joint (End Sites too), with a NodeAttribute "LimbNode" (TypeFlags
//   "Skeleton"): Lcl Translation the joint's local translation at frame 0, Lcl Rotation and
//   PreRotation zero (the rest pose is the clip's zero pose, as in BVH), RotationOrder the
//   joint's Euler order (channels Z X Y, R = Rz Rx Ry, are FBX's eEulerYXZ).
// - AnimationStack (named after the take) > AnimationLayer "BaseLayer" > AnimationCurveNodes:
//   "R" on every joint but End Sites (Lcl Rotation, degrees, in the joint's order; joints whose
//   rotation channels are not three distinct axes are converted to Z X Y), "T" on the roots and
//   on joints whose position channels change (Lcl Translation, file units). Each has three
//   AnimationCurves d|X, d|Y, d|Z with a key per frame at KeyTime = round(f x 46186158000 / fps),
//   KeyValueFloat, linear interpolation. Angles are unwrapped frame to frame.
// - Definitions (object counts), FBXHeaderExtension, Documents, References, Connections
//   (OO child -> parent; OP curve node -> model property, curve -> curve node channel) and Takes.
#include <string>

#include "engine/base/clip.h"

namespace mostyle {

struct FbxWriteOptions {
  int version = 7400;     // 7400 (32-bit record offsets) or 7500 (64-bit)
  bool compress = true;   // key arrays over 128 bytes zlib-compressed (as the FBX SDK writes them)
};

// The FBX SDK's rate codes (GlobalSettings TimeMode) for the rates it names; 14 (custom) for
// any other, whose rate is then CustomFrameRate.
int fbx_time_mode(double fps);

// The clip as the bytes of a binary FBX file; its animation stack and armature are named
// `take_name`. Throws InputError naming clip.source on a skeleton without joints, a rate that
// is not positive, a take longer than FBX's 64-bit key times reach, a value that is not finite,
// a joint name with bytes FBX names cannot hold (a NUL), or a file past 4 GB at version 7400. O(frames x joints).
std::string format_fbx(const Clip& clip, const std::string& take_name, const FbxWriteOptions& options = {});

// Writes `path` atomically, the take named after the file's stem. Throws InputError as
// format_fbx does, or when the file cannot be written.
void write_fbx_file(const Clip& clip, const std::string& path, const FbxWriteOptions& options = {});

}  // namespace mostyle
