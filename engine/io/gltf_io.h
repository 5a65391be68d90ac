#pragma once
// Reading and writing glTF 2.0 skeletal animation: `.glb`, and `.gltf` with its
// `.bin` or data URIs. Reading parses with tinygltf (Debian's libtinygltf-dev, a faithful reader
// of the format) and keeps only nodes, the skins' joint lists and animations: meshes, bind
// matrices, cameras, materials and images are never decoded, so a file whose mesh data is
// faulty still gives its animation.
// Writing is our own (nlohmann json): the skeleton as nodes under one armature node and as a
// skin, one animation, laid out so the Khronos validator reports no error and no warning.
#include <cstddef>
#include <string>
#include <string_view>

#include "engine/base/clip.h"
#include "engine/base/memory_limit.h"
#include "engine/io/scene_animation.h"

namespace mostyle {

// Parses glTF bytes: a GLB container, or glTF JSON text (bytes not starting with "glTF").
// `source` names the file in messages; `base_dir` is where a .gltf's relative buffer URIs are
// found ("": no file is read, a buffer URI that is not a data URI is an error). Accessors may
// be float or normalized integers (KHR_mesh_quantization), interleaved (byteStride) or not; sparse accessors are refused. Nodes come back parents first;
// a node without a name is called "node N" (its index); lengths are metres
// (AnimatedScene::metres_per_unit 1), so a file mostyle wrote from a take in centimetres reads
// back in metres, the source's positions times 0.01. Throws InputError
// "SOURCE: what is wrong" (one sentence, tinygltf's first error line quoted) on a file that is
// not glTF, is cut, has a bad hierarchy (a cycle, a node with two parents), an animation
// channel pointing outside the file, accessor data outside its buffer, or no animation at all.
// Library exceptions never escape. O(size); memory: the file's buffers, bounded by max_bytes.
AnimatedScene parse_gltf(std::string_view bytes, const std::string& source, const std::string& base_dir = "",
                         size_t max_bytes = kDefaultMaxBytes);

// Reads a .glb or .gltf file (refused before reading when larger than max_bytes).
AnimatedScene read_gltf_file(const std::string& path, size_t max_bytes = kDefaultMaxBytes);

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
