#pragma once
// Reading glTF 2.0 skeletal animation (gltf_write.h writes it): `.glb`, and `.gltf` with its
// `.bin` or data URIs. Reading parses with tinygltf (Debian's libtinygltf-dev, a faithful reader
// of the format) and keeps only nodes, the skins' joint lists and animations: meshes, bind
// matrices, cameras, materials and images are never decoded, so a file whose mesh data is
// faulty still gives its animation.
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

}  // namespace mostyle
