#include "app/cli/cli_clip_commands.h"

#include <cmath>
#include <filesystem>
#include <iostream>
#include <optional>

#include <nlohmann/json.hpp>

#include "app/cli/cli_common.h"
#include "app/cli/cli_pipeline_common.h"
#include "app/cli/take_info.h"
#include "engine/export/export_frames.h"
#include "engine/base/numbers.h"
#include "engine/io/bvh/bvh_read.h"
#include "engine/kinematics/convert.h"
#include "engine/base/error.h"
#include "engine/io/motion_file.h"
#include "engine/kinematics/euler.h"
#include "engine/kinematics/kinematics.h"
#include "engine/kinematics/resample.h"
#include "engine/kinematics/units.h"
#include "engine/prepare/major_skeleton.h"

namespace mostyle::cli {
namespace {

std::string channel_list(const Joint& j) {
  std::string s;
  for (Channel c : j.channels) {
    if (!s.empty()) s += ' ';
    s += channel_name(c);
  }
  return s;
}

// CLI::PositiveNumber lets "nan" through (every comparison with it is false).
CLI::Validator positive_finite_rate() {
  return CLI::Validator(
      [](std::string& text) {
        double v = 0;
        if (CLI::detail::lexical_cast(text, v) && v > 0 && std::isfinite(v)) return std::string();
        return "expected a positive frame rate, found " + text;
      },
      "POSITIVE");
}

}  // namespace

namespace {

void print_info_json(const std::string& path, const FileInfo& info) {
  // Joint names are bytes from the file: invalid UTF-8 is replaced, not thrown on.
  std::cout << info_json(path, info).dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) << "\n";
}

// Every joint but the End Sites, indented by depth, with its channels.
void print_hierarchy(const Skeleton& s) {
  std::cout << "  hierarchy:\n";
  // Depths in one pass (parents come first): walking up per joint is quadratic in depth.
  std::vector<int> depths(s.joints.size(), 0);
  for (size_t i = 0; i < s.joints.size(); ++i)
    if (s.joints[i].parent >= 0) depths[i] = depths[s.joints[i].parent] + 1;
  for (size_t i = 0; i < s.joints.size(); ++i) {
    const Joint& jt = s.joints[i];
    if (jt.end_site) continue;
    std::cout << "    " << std::string(std::min(depths[i], 16) * 2, ' ') << jt.name << "  [" << channel_list(jt) << "]";
    if (!joint_rotation_order(jt).empty()) std::cout << " order " << joint_rotation_order(jt);
    std::cout << "\n";
  }
}

void print_info_text(const std::string& path, const FileInfo& info) {
  const Clip& clip = *info.clip;
  const Skeleton& s = clip.skeleton;
  const int end_sites = static_cast<int>(s.joints.size()) - s.joint_count_without_end_sites();
  std::cout << path << "\n"
            << "  joints: " << s.joint_count_without_end_sites() << " (+" << end_sites << " End Sites), "
            << info.origin.words << (s.joints.empty() ? "" : ", root '" + s.joints[0].name + "'") << "\n"
            << "  takes: " << info.takes.size() << (info.takes.size() > 1 ? ", every one on this skeleton" : "")
            << "\n";
  for (const TakeInfo& t : info.takes) {
    std::cout << "    " << t.name << "  (" << duration_in_words(t.seconds) << ", " << t.keyframes << " keyframes";
    if (t.moves >= 0) std::cout << ", moves " << t.moves << " joints";
    std::cout << ")\n";
  }
  std::cout << "  channels per frame: " << s.channel_count << "\n"
            << "  frames: " << clip.frames() << "\n"
            << "  frame time: " << number(clip.frame_time) << " s (" << number(clip.fps()) << " fps)\n"
            << "  duration: " << duration_in_words(motion_length_s(clip.frames(), clip.fps())) << "\n"
            << "  units (guess): " << info.units.name << " (height " << number(info.units.height) << ")\n"
            << "  cycles: "
            << (info.cycles ? cycles_summary(*info.cycles, clip.fps(), clip.frames()) : "unknown: " + info.no_cycles)
            << "\n";
  if (info.cycles) std::cout << "  structure: " << action_structure_summary(*info.cycles, clip.fps()) << "\n";
  std::cout << "  major joints: " << info.majors.how << "\n";
  for (int m = 0; m < kMajorJointCount; ++m) {
    if (!info.majors.has(m) && info.majors.source[m] == MajorSource::kNone) continue;
    std::cout << "    " << major_joint_name(m) << ": "
              << (info.majors.has(m) ? s.joints[info.majors.joint[m]].name : std::string("-")) << " ("
              << major_source_name(info.majors.source[m]) << ")\n";
  }
  print_hierarchy(s);
}

}  // namespace

void add_info_command(CLI::App& app, std::function<int()>* run) {
  auto* cmd = app.add_subcommand(
      "info", "Print a file's skeleton, its animations, and one take's channels, frames, units and major joints");
  auto path = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  auto take = std::make_shared<std::string>();
  auto fps = std::make_shared<double>(0.0);
  auto mapping = std::make_shared<std::string>();
  cmd->add_option("FILE", *path, "BVH, FBX, GLB or glTF file (FILE#ANIMATION picks one animation)")->required();
  cmd->add_flag("--json", *json, "Print JSON");
  cmd->add_option("--take", *take, "The animation to describe (FBX, glTF); default the first");
  cmd->add_option("--fps", *fps, "Rate to sample FBX and glTF keys at; default the file's")->check(positive_finite_rate());
  cmd->add_option("--mapping", *mapping, "Major-joint mapping file (see assets/mappings)");
  cmd->callback([=] {
    *run = [=] {
      const FileInfo info = read_file_info(*path, *take, *fps, *mapping);
      if (*json) print_info_json(*path, info);
      else print_info_text(*path, info);
      return 0;
    };
  });
}

void add_fk_command(CLI::App& app, std::function<int()>* run) {
  auto* cmd = app.add_subcommand("fk", "Write every joint's global position per frame as CSV");
  auto path = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>();
  auto take = std::make_shared<std::string>();
  auto fps = std::make_shared<double>(0.0);
  cmd->add_option("FILE", *path, "BVH, FBX, GLB or glTF file (FILE#ANIMATION picks one animation)")->required();
  cmd->add_option("--out", *out, "CSV file: frame,joint,x,y,z (file units and axes)")->required();
  cmd->add_option("--take", *take, "The animation to read (FBX, glTF); default the first");
  cmd->add_option("--fps", *fps, "Frame rate of the rows; default the file's")->check(positive_finite_rate());
  cmd->callback([=] {
    *run = [=] {
      Clip clip = load_clip(*path, *take, *fps);
      if (*fps > 0 && motion_format(split_take_path(*path).path) == MotionFormat::kBvh) clip = resample_clip(clip, *fps);
      std::vector<int> joints;
      std::vector<std::string> names;
      for (size_t i = 0; i < clip.skeleton.joints.size(); ++i) {
        if (clip.skeleton.joints[i].end_site) continue;
        joints.push_back(static_cast<int>(i));
        names.push_back(clip.skeleton.joints[i].name);
      }
      write_output(*out, positions_csv(joint_positions(clip), joints, names));
      return 0;
    };
  });
}

void add_convert_command(CLI::App& app, std::function<int()>* run) {
  auto* cmd = app.add_subcommand("convert", "Rewrite a take as BVH, FBX or glTF, in another Euler order or frame rate");
  auto in = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>();
  auto order = std::make_shared<std::string>();
  auto fps = std::make_shared<double>(0.0);
  auto take = std::make_shared<std::string>();
  cmd->add_option("IN", *in, "BVH, FBX, GLB or glTF file to read (FILE#ANIMATION picks one animation)")->required();
  cmd->add_option("OUT", *out, "File to write: .bvh as BVH, .fbx as binary FBX 7.4, .glb or .gltf (with its .bin) as glTF 2.0")
      ->required()
      ->check(written_motion_format());
  cmd->add_option("--take", *take, "The animation to read (FBX, glTF); default the first");
  cmd->add_option("--order", *order, "Rotation order: XYZ, XZY, YXZ, YZX, ZXY or ZYX")
      ->check(CLI::IsMember({"XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX"}, CLI::ignore_case));
  cmd->add_option("--fps", *fps, "Frame rate of the output")->check(positive_finite_rate());
  cmd->callback([=] {
    *run = [=] {
      Clip clip = load_clip(*in, *take, *fps);
      if (*fps > 0 && motion_format(split_take_path(*in).path) == MotionFormat::kBvh) clip = resample_clip(clip, *fps);
      if (!order->empty()) {
        EulerOrder o;
        parse_euler_order(*order, &o);
        clip = convert_euler_order(clip, o);
      }
      write_motion_file(clip, *out);
      return 0;
    };
  });
}

}  // namespace mostyle::cli
