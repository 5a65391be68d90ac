#include "engine/io/motion_file.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

#include "engine/io/bvh/bvh_read.h"
#include "engine/io/bvh/bvh_write.h"
#include "engine/base/error.h"
#include "engine/io/fbx/fbx_read.h"
#include "engine/io/fbx/fbx_write.h"
#include "engine/io/gltf/gltf_read.h"
#include "engine/io/gltf/gltf_write.h"

namespace mostyle {
namespace {

std::string lower_extension(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  const size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

std::string quoted_list(const std::vector<std::string>& names, size_t skip) {
  std::string out;
  int shown = 0;
  for (size_t i = 0; i < names.size(); ++i) {
    if (i == skip) continue;
    if (shown == 8) {
      out += ", ...";
      break;
    }
    out += (shown++ ? ", '" : "'") + names[i] + "'";
  }
  return out;
}

}  // namespace

MotionFormat motion_format(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".fbx") return MotionFormat::kFbx;
  if (ext == ".glb" || ext == ".gltf") return MotionFormat::kGltf;
  return MotionFormat::kBvh;
}

bool is_motion_file(const std::string& path) {
  const std::string ext = lower_extension(path);
  return ext == ".bvh" || ext == ".fbx" || ext == ".glb" || ext == ".gltf";
}

bool has_takes(MotionFormat format) { return format != MotionFormat::kBvh; }

TakePath split_take_path(const std::string& text) {
  const size_t hash = text.find('#', text.find_last_of('/') == std::string::npos ? 0 : text.find_last_of('/'));
  if (hash == std::string::npos) return {text, ""};
  const std::string path = text.substr(0, hash);
  if (!has_takes(motion_format(path)) || lower_extension(path).empty()) return {text, ""};
  std::error_code ec;
  if (std::filesystem::exists(text, ec)) return {text, ""};
  return {path, text.substr(hash + 1)};
}

std::string take_label(const std::string& text) {
  const TakePath tp = split_take_path(text);
  return tp.take.empty() ? std::filesystem::path(tp.path).stem().string() : tp.take;
}

std::vector<std::string> distinct_take_labels(const std::vector<std::string>& texts) {
  std::vector<std::string> labels;
  for (const std::string& t : texts) labels.push_back(take_label(t));
  if (labels.size() < 2) return labels;
  size_t common = labels.front().size();
  for (const std::string& l : labels) {
    size_t n = 0;
    while (n < common && n < l.size() && l[n] == labels.front()[n]) ++n;
    common = n;
  }
  for (const std::string& l : labels)
    if (l.size() <= common) return labels;  // a label all shared: nothing tells the takes apart better
  while (common > 0 && labels.front()[common - 1] != '_' && labels.front()[common - 1] != '-') --common;
  for (std::string& l : labels)
    if (common < l.size()) l = l.substr(common);
  return labels;
}

std::string join_take_path(const std::string& path, const std::string& take) {
  return take.empty() ? path : path + "#" + take;
}

AnimatedScene read_animated_scene(const std::string& path, size_t max_bytes) {
  switch (motion_format(path)) {
    case MotionFormat::kFbx: return read_fbx_file(path, max_bytes);
    case MotionFormat::kGltf: return read_gltf_file(path, max_bytes);
    case MotionFormat::kBvh: break;
  }
  throw InputError(path + ": a BVH file holds one take, not animations");
}

Clip read_motion_file(const std::string& text, std::vector<std::string>* warnings, const MotionReadOptions& options,
                      std::vector<std::string>* notes) {
  const TakePath tp = split_take_path(text);
  const std::string take_name = options.take.empty() ? tp.take : options.take;
  const MotionFormat format = motion_format(tp.path);
  if (format == MotionFormat::kBvh) {
    if (!take_name.empty())
      throw InputError(tp.path + ": a BVH file holds one take, so it has no animation '" + take_name + "'");
    BvhReadOptions bvh;
    bvh.max_bytes = options.max_bytes;
    return read_bvh_file(tp.path, warnings, bvh);
  }
  const AnimatedScene scene = read_animated_scene(tp.path, options.max_bytes);
  std::vector<std::string> names;
  for (const SceneTake& t : scene.takes) names.push_back(t.name);
  int take = 0;
  if (!take_name.empty()) {
    take = find_take(scene, take_name);
    if (take < 0)
      throw InputError(tp.path + ": has no animation '" + take_name + "'; it has " + quoted_list(names, SIZE_MAX));
  } else if (names.size() > 1 && notes != nullptr) {
    notes->push_back(tp.path + ": read animation '" + names[0] + "' (the first); the file also has " +
                     quoted_list(names, 0) + ": pick one with FILE#NAME or --take NAME");
  }
  SceneClipOptions so;
  so.fps = options.fps;
  so.max_bytes = options.max_bytes;
  Clip clip = scene_take_to_clip(scene, take, so);
  clip.source = join_take_path(tp.path, take_name.empty() && names.size() > 1 ? names[0] : take_name);
  return clip;
}

std::vector<TakeInfo> read_motion_takes(const std::string& path, const MotionReadOptions& options) {
  const TakePath tp = split_take_path(path);
  if (motion_format(tp.path) == MotionFormat::kBvh) {
    BvhReadOptions bvh;
    bvh.max_bytes = options.max_bytes;
    const Clip clip = read_bvh_file(tp.path, nullptr, bvh);
    TakeInfo info;
    info.name = std::filesystem::path(tp.path).stem().string();
    info.seconds = clip.frames() > 1 ? (clip.frames() - 1) * clip.frame_time : 0.0;
    info.keyframes = clip.frames();
    return {info};
  }
  return scene_take_infos(read_animated_scene(tp.path, options.max_bytes));
}

void write_motion_file(const Clip& clip, const std::string& path) {
  switch (motion_format(path)) {
    case MotionFormat::kGltf: write_gltf_file(clip, path); return;
    case MotionFormat::kFbx: write_fbx_file(clip, path); return;
    case MotionFormat::kBvh: break;
  }
  write_bvh_file(clip, path);
}

bool is_written_motion_path(const std::string& path) { return is_motion_file(path); }

}  // namespace mostyle
