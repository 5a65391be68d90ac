#pragma once
// The one place motion files are opened: BVH, FBX, glTF (.glb, .gltf), chosen by
// the file's extension, and FILE#ANIMATION naming one take of a file that holds several. Every
// consumer (the CLI's commands, batch lines, the worker behind the editor) reads through here.
#include <cstddef>
#include <string>
#include <vector>

#include "engine/base/clip.h"
#include "engine/base/memory_limit.h"
#include "engine/io/scene_animation.h"

namespace mostyle {

enum class MotionFormat { kBvh, kFbx, kGltf };

// The format a path's extension names (case-insensitive: .bvh, .fbx, .glb, .gltf); kBvh for
// any other, so the BVH reader's messages say what is wrong with it.
MotionFormat motion_format(const std::string& path);

// True for the extensions the readers take (.bvh, .fbx, .glb, .gltf): what file lists show.
bool is_motion_file(const std::string& path);

// True for formats that hold several takes (FBX, glTF).
bool has_takes(MotionFormat format);

// "walk.glb#run" -> {"walk.glb", "run"}. A '#' splits only when what is before it ends in
// .fbx, .glb or .gltf and the whole text is not itself an existing file; else take is "".
struct TakePath {
  std::string path;
  std::string take;
};
TakePath split_take_path(const std::string& text);

// What a take is called on screen: the animation's name for FILE#ANIMATION ("run"), else the
// file's name without folder and extension ("walk" for "data/walk.bvh").
std::string take_label(const std::string& text);
// Each take's label without the start every label shares up to a '_' or '-'
// ("cmu142_walk_happy", "cmu142_walk_marching": "happy", "marching"), so that names fit narrow
// columns; a label that would be empty stays whole. O(total length).
std::vector<std::string> distinct_take_labels(const std::vector<std::string>& texts);

// "walk.glb" + "run" -> "walk.glb#run"; the path alone when take is empty.
std::string join_take_path(const std::string& path, const std::string& take);

struct MotionReadOptions {
  size_t max_bytes = kDefaultMaxBytes;  // the file and the frames it makes (MOSTYLE_MAX_MEMORY_MB)
  double fps = 0.0;   // FBX/glTF sampling rate; 0: the file's own (scene_animation.h). BVH: unused
  std::string take;   // the animation to read; "" takes FILE#ANIMATION's, else the first
};

// Reads one take. `text` is a path or FILE#ANIMATION. BVH goes to bvh_read.h read_bvh_file
// (its recoverable defects appended to *warnings). For FBX and glTF: the take named by
// options.take or by '#' (options.take wins), else the first, with a sentence naming the others
// appended to *notes ("walk.glb: read animation 'a' (the first); the file also has 'b', 'c':
// pick one with FILE#NAME or --take NAME"). Throws InputError naming the file (and animation):
// unknown take (listing the takes), unreadable file, no skeleton, memory over the limit.
Clip read_motion_file(const std::string& text, std::vector<std::string>* warnings = nullptr,
                      const MotionReadOptions& options = {}, std::vector<std::string>* notes = nullptr);

// The takes of a file: one for a BVH (named after the file's stem, its length), every
// animation of an FBX or glTF file. Throws InputError as read_motion_file does.
std::vector<TakeInfo> read_motion_takes(const std::string& path, const MotionReadOptions& options = {});

// The animated scene of an FBX or glTF file (read_fbx_file or read_gltf_file by extension).
// Throws InputError for a BVH path or an unreadable file.
AnimatedScene read_animated_scene(const std::string& path, size_t max_bytes = kDefaultMaxBytes);

// Writes a clip by the extension of `path`: .glb/.gltf as glTF 2.0 (gltf_write.h
// write_gltf_file), .fbx as binary FBX 7.4 (fbx_write.h write_fbx_file), anything else as BVH
// (bvh_write.h write_bvh_file). Atomic; throws InputError.
void write_motion_file(const Clip& clip, const std::string& path);

// True when `path` ends in an extension a motion is written in (.bvh, .fbx, .glb, .gltf,
// case-insensitive): the outputs the CLI and the editor accept.
bool is_written_motion_path(const std::string& path);
// The formats written, for messages: "BVH (.bvh), FBX (.fbx) and glTF 2.0 (.glb, .gltf)".
inline constexpr const char* kWrittenMotionFormats = "BVH (.bvh), FBX (.fbx) and glTF 2.0 (.glb, .gltf)";

}  // namespace mostyle
