#pragma once
// Writing glTF 2.0 skeletal animation (gltf_read.h reads it), our own (nlohmann json): the
// skeleton as nodes under one armature node and as a skin, one animation, laid out so the
// Khronos validator reports no error and no warning.
#include <string>

#include "engine/base/clip.h"
#include "engine/base/memory_limit.h"
#include "engine/io/scene_animation.h"

namespace mostyle {

struct GltfWriteOptions {
  // Also a stick figure (a thin double pyramid per bone, skinned to it) on a node of its own,
  // for readers that build a skeleton only for a skinned mesh (three.js makes Bones from the
  // skin's joints either way, a THREE.Skeleton only for a SkinnedMesh). Off by default: the
  // glTF importer of Debian 12's Blender 3.4 fails on any mesh with its default shading
  // setting (numpy 1.24 has no np.bool), while the skin alone imports as an armature.
  bool bone_mesh = false;
};

// A clip as one glTF document, in metres (glTF's unit): lengths are the clip's file units times
// kinematics/units.h metres_per_unit (the unit its file states, else the guess from its size;
// as they are when neither tells), so a BVH in centimetres stands as tall in Blender as its
// FBX does. Nodes 0 .. J-1 are the skeleton's joints (End Sites too) with
// their rest translations (each joint's local translation at frame 0), children in skeleton
// order; node J, named `animation_name`, is the armature: the parent of the skeleton's roots,
// without a transform, and the one root of the scene. Skin 0 lists all J joints, End Sites too
// (Blender makes bones of a skin's joints only, Empties of other nodes), its skeleton is node
// J, its inverse bind matrices the inverses of the joints' rest world transforms (so Blender
// imports one armature whose bones carry one action). One animation named
// `animation_name` whose samplers are LINEAR, key times i / clip.fps() (float32, min and max
// given): the root's translation, every other joint's translation when its position channels
// change, and every joint's rotation but End Sites' as a unit quaternion, the sign chosen so
// consecutive keys have a non-negative dot product (no flips in slerp). options.bone_mesh adds
// mesh 0 on node J+1, a second root. `bin_uri`: "" writes the binary chunk of a GLB (the
// buffer has no uri); otherwise the JSON's buffer names that file. Returns the JSON text and
// fills *bin with the buffer's bytes. O(frames x joints).
std::string format_gltf(const Clip& clip, const std::string& animation_name, const std::string& bin_uri,
                        std::string* bin, const GltfWriteOptions& options = {});

// The same as one GLB container (12-byte header, JSON chunk padded with spaces, BIN chunk).
std::string format_glb(const Clip& clip, const std::string& animation_name, const GltfWriteOptions& options = {});

// Writes `path` atomically: `.glb` as one file; `.gltf` with its buffer beside it in
// `<stem>.bin` (written first, also atomically). The animation is named after the file's stem.
// Throws InputError when the path ends in neither or a file cannot be written.
void write_gltf_file(const Clip& clip, const std::string& path, const GltfWriteOptions& options = {});

}  // namespace mostyle
