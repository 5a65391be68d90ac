#pragma once
// Keyed node animation as FBX and glTF files hold it: a tree of nodes with rest transforms, the
// nodes the file's skins deform with, and takes whose tracks key a node's translation, rotation
// or scale at times. The readers (gltf_read.h, fbx_read.h) fill this value; scene_skeleton finds the
// file's one skeleton and scene_take_to_clip samples one take on it at a frame rate into the
// engine's Clip, so every later stage sees what a BVH file gives, and every take of a file has
// the same joints.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <string>
#include <vector>

#include "engine/base/clip.h"
#include "engine/base/memory_limit.h"

namespace mostyle {

// glTF's sampler interpolations (FBX keys, as assimp gives them, are linear).
enum class KeyInterpolation { kStep, kLinear, kCubicSpline };
enum class TrackTarget { kTranslation, kRotation, kScale };

// One animated property of one node.
struct KeyTrack {
  int node = -1;  // index into AnimatedScene::nodes
  TrackTarget target = TrackTarget::kTranslation;
  KeyInterpolation interpolation = KeyInterpolation::kLinear;
  std::vector<double> times;  // K key times, seconds, strictly increasing
  // Rows are keys, columns the value: 3 (x, y, z) for translation and scale, 4 (x, y, z, w) for
  // a rotation quaternion. kCubicSpline: 3K rows, (in-tangent, value, out-tangent) per key as
  // glTF stores them; tangents are per second.
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> values;
};

struct SceneNode {
  std::string name;  // as in the file
  int parent = -1;   // index into AnimatedScene::nodes, -1 for a root
  // Rest transform: local = T * R * S (file units).
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
  // A bone of the file's skeleton wherever it hangs in it, keyed or not (FBX: a LimbNode, no
  // Null nor mesh), so the end bones below the keyed joints (Mixamo's HeadTop_End) stay in it.
  // glTF's bones are its skins' joints: false.
  bool limb = false;
};

struct SceneTake {
  std::string name;  // as in the file ("animation 2" when it has none)
  std::vector<KeyTrack> tracks;
};

struct AnimatedScene {
  std::string source;            // file name for messages
  std::vector<SceneNode> nodes;  // parents before children
  std::vector<SceneTake> takes;  // in file order
  double frame_rate = 0.0;       // the rate the file states (FBX time mode), 0 when none
  // A node that stands for the whole scene (assimp's root node), never a skeleton's root
  // unless a take keys it; -1 when the file has none (glTF: the scene's nodes are roots).
  int scene_root = -1;
  // The nodes the file's skins name as their joints (glTF skins, FBX deformers), each once, in
  // node order; empty when the file has no skin.
  std::vector<int> skin_joints;
  // Metres per unit of the nodes' translations where the format fixes it (glTF: 1), else 0; it
  // becomes the clips' Skeleton::metres_per_unit.
  double metres_per_unit = 0.0;
};

// The file's one skeleton, which every take is read on.
struct SceneSkeleton {
  std::vector<int> nodes;   // joint index -> node: depth-first from the root, parents first, siblings in file order
  bool from_skins = false;  // the skins' joints; else the nodes the takes key
  int root() const { return nodes.front(); }
};

// The skeleton of a file: the joints of its skins and the nodes between them, rooted at their
// lowest common ancestor; in a file without skins, the nodes any take keys (the union over all
// takes) and the nodes between them, likewise; then the limbs (SceneNode::limb) that hang from
// those with only limbs between, keyed or not. Nodes above the root only place it. Where those
// nodes have no common ancestor but the scene root (several characters in one file), the one
// skeleton among them whose nodes take `take` keys (every take of that character gets the same).
// Throws InputError naming the source when there are several skeletons and `take` is -1 or keys
// more than one, when a track names a node the file does not have, or when the nodes do not
// come parents first. O(nodes + tracks).
SceneSkeleton scene_skeleton(const AnimatedScene& scene, int take = -1);

// One take as `info` lists it.
struct TakeInfo {
  std::string name;
  double seconds = 0.0;  // last key time - first key time
  int keyframes = 0;     // the most keyframes on one track
  int moves = 0;         // joints of the file's skeleton the take keys (a BVH's: every joint); -1 when not known
};
// Every take of the scene; `moves` is -1 for a take whose skeleton cannot be found.
std::vector<TakeInfo> scene_take_infos(const AnimatedScene& scene);

// The take named `name`: its index, or -1.
int find_take(const AnimatedScene& scene, const std::string& name);

// The value of a track at time t (seconds): STEP holds the key at or before t; LINEAR
// interpolates (slerp on the shorter arc for rotations); CUBICSPLINE is glTF's Hermite spline,
// tangents scaled by the key interval (glTF 2.0 Appendix C). Before the first key the first
// value, after the last the last. A key within `snap` seconds of t is taken as it is: key times
// stored as float32 or FBX ticks miss the sampling grid by a hair, and the next key may be far
// (assimp adds keys between two frames where an Euler curve turns more than 180 degrees).
// Rotations come back normalized. O(log K).
// Returns x, y, z (and w for a rotation; 0 for translation and scale).
Eigen::Vector4d sample_track(const KeyTrack& track, double t, double snap = 0.0);

struct SceneClipOptions {
  double fps = 0.0;  // sampling rate; 0: the file's (AnimatedScene::frame_rate), else the keys' spacing, else 30
  size_t max_bytes = kDefaultMaxBytes;  // the sampled frames (frames x channels x 8) may take at most this
};

// Samples take `take` at options.fps from its first key to its last into a Clip on the file's
// skeleton (scene_skeleton), the same joints and channels for every take of it; nodes above
// the root only place it (their transforms, scale included, are folded into the root's
// channels), and a joint the take does not key keeps its rest transform. Every joint gets
// rotation channels Z X Y (degrees, unwrapped frame to frame); the root gets position channels
// in world units; a joint whose offset from its parent moves off its rest offset in any take
// (translation keys beyond 1e-4 of the skeleton's size, or scale keys above it beyond 1e-4)
// keeps position channels too. Offsets are each joint's rest translation in its parent's frame, world units,
// and Joint::rest_rotation the rest rotation, so positions by FK equal the file's world
// positions of those nodes (under uniform scale) and rest_positions its rest pose.
// Throws InputError naming the source and the take when the take keys no node of the skeleton
// or above it, as scene_skeleton does, on a bad track (times not increasing, non-finite values,
// wrong sizes) or when the frames would take more than options.max_bytes (checked before
// allocating them). A leaf of the skeleton that no take keys and whose offset never moves is an
// End Site (Joint::end_site, no channels, named as its node), as BVH has it: a file mostyle
// wrote from a BVH reads back with its End Sites, and Mixamo's end bones read as theirs. The
// skeleton's metres_per_unit is the scene's. O(frames x nodes + keys of all takes).
Clip scene_take_to_clip(const AnimatedScene& scene, int take, const SceneClipOptions& options = {});

// The rate a take is sampled at when the caller gives none: scene.frame_rate; else, when the
// track with the most keys has them evenly spaced (within 1% of a step), keys minus one over its
// span, unrounded, so samples land on keys (120.0048 for a BVH's 0.008333 s written as glTF);
// else one over the median spacing of the take's keys (snapped by frame_rate_from_frame_time);
// else 30. Rates outside [1, 1000] give 30.
double default_take_rate(const AnimatedScene& scene, int take);

}  // namespace mostyle
