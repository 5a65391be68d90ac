#pragma once
// Reading FBX skeletal animation, binary and ASCII, with assimp (Debian's
// libassimp-dev 5.2). assimp folds each node's pre- and post-rotation, pivots and offsets into
// one transform (AI_CONFIG_IMPORT_FBX_PRESERVE_PIVOTS off, so no "$AssimpFbx$" helper nodes)
// and its keys; the unit scale stays in the nodes' transforms, which scene_take_to_clip folds
// into world positions. Each animation stack is a take; its keys are in the file's time mode,
// which is the rate the file states. Meshes, materials, textures, cameras and lights are not
// read.
#include <cstddef>
#include <string>
#include <string_view>

#include "engine/base/memory_limit.h"
#include "engine/io/scene_animation.h"

namespace mostyle {

// Parses FBX bytes. `source` names the file in messages. Throws InputError
// "SOURCE: not a readable FBX file: reason" on anything assimp refuses (cut, corrupt, not FBX),
// and "SOURCE: has no animation" when it holds none. Library exceptions never escape.
// Memory: assimp's scene, a few times the file's size.
AnimatedScene parse_fbx(std::string_view bytes, const std::string& source);

// Reads an .fbx file (refused before reading when larger than max_bytes).
AnimatedScene read_fbx_file(const std::string& path, size_t max_bytes = kDefaultMaxBytes);

}  // namespace mostyle
