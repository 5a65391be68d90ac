#include "app/cli/take_info.h"

#include <filesystem>

#include "app/cli/cli_common.h"
#include "app/cli/cli_pipeline_common.h"
#include "engine/base/error.h"
#include "engine/export/export_frames.h"
#include "engine/io/motion_file.h"
#include "engine/base/numbers.h"

namespace mostyle::cli {
namespace {

SkeletonOrigin skeleton_origin(MotionFormat format, const SceneSkeleton* scene) {
  if (format == MotionFormat::kBvh || scene == nullptr) return {"hierarchy", "the file's hierarchy"};
  if (scene->from_skins) return {"skins", "the joints of the file's skins"};
  return {"animated nodes", "the nodes the animations key"};
}

}  // namespace

std::string joint_rotation_order(const Joint& joint) {
  std::string s;
  for (Channel c : joint.channels)
    if (is_rotation(c)) s += static_cast<char>('X' + channel_axis(c));
  return s;
}

FileInfo read_file_info(const std::string& path, const std::string& take, double fps, const std::string& mapping) {
  FileInfo info;
  info.clip = std::make_shared<const Clip>(load_clip(path, take, fps));
  const Clip& clip = *info.clip;
  const MappingOverrides overrides = load_mapping(mapping);
  info.majors = map_major_joints(clip, overrides.entries.empty() ? nullptr : &overrides);
  try {
    info.cycles = take_cycles(info.clip);
  } catch (const InputError& e) {
    info.no_cycles = e.what();
  }
  // A BVH is one take, the clip just read (not read again: a BVH may be 100 MB). An FBX or
  // glTF file's animations all play on its one skeleton.
  const TakePath file = split_take_path(path);
  const MotionFormat format = motion_format(file.path);
  std::optional<SceneSkeleton> scene_skeleton_found;
  if (has_takes(format)) {
    const AnimatedScene scene = read_animated_scene(file.path, motion_read_options_from_environment().max_bytes);
    info.takes = scene_take_infos(scene);
    const std::string take_name = take.empty() ? file.take : take;
    scene_skeleton_found = scene_skeleton(scene, take_name.empty() ? 0 : find_take(scene, take_name));
  } else {
    info.takes.push_back({std::filesystem::path(file.path).stem().string(), motion_length_s(clip.frames(), clip.fps()),
                          clip.frames(), clip.skeleton.joint_count_without_end_sites()});
  }
  info.origin = skeleton_origin(format, scene_skeleton_found ? &*scene_skeleton_found : nullptr);
  info.units = guess_units(clip);
  return info;
}

Json info_json(const std::string& path, const FileInfo& info) {
  const Clip& clip = *info.clip;
  const Skeleton& s = clip.skeleton;
  Json j;
  j["file"] = path;
  j["frames"] = clip.frames();
  j["frame_time"] = clip.frame_time;
  j["fps"] = clip.fps();
  j["duration_s"] = motion_length_s(clip.frames(), clip.fps());  // first frame to last
  j["channels"] = s.channel_count;
  j["units_guess"] = info.units.name;
  j["height"] = info.units.height;
  j["skeleton"] = {{"joints", s.joint_count_without_end_sites()},
                   {"end_sites", static_cast<int>(s.joints.size()) - s.joint_count_without_end_sites()},
                   {"root", s.joints.empty() ? "" : s.joints[0].name},
                   {"from", info.origin.key}};
  auto& tk = j["takes"] = Json::array();
  for (const TakeInfo& t : info.takes)
    tk.push_back({{"name", t.name}, {"seconds", t.seconds}, {"keyframes", t.keyframes}, {"moves", t.moves}});
  if (info.cycles) {
    j["cycles"] = cycles_json(*info.cycles, clip.fps());
    j["structure"] = action_structure_summary(*info.cycles, clip.fps());
  } else {
    j["cycles"] = {{"kind", "unknown"}, {"reason", info.no_cycles}};
  }
  j["major_joints"] = major_joints_json(info.majors, s);
  auto& joints = j["joints"] = Json::array();
  for (const Joint& jt : s.joints) {
    if (jt.end_site) continue;
    Json o;
    o["name"] = jt.name;
    o["parent"] = jt.parent < 0 ? Json() : Json(s.joints[jt.parent].name);
    o["offset"] = {jt.offset.x(), jt.offset.y(), jt.offset.z()};
    auto& ch = o["channels"] = Json::array();
    for (Channel c : jt.channels) ch.push_back(channel_name(c));
    o["rotation_order"] = joint_rotation_order(jt);
    joints.push_back(o);
  }
  return j;
}

}  // namespace mostyle::cli
