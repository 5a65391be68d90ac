#include "tests/fuzz/fuzz_readers.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "app/batch/job_line.h"
#include "engine/io/bvh/bvh_read.h"
#include "engine/io/bvh/bvh_write.h"
#include "engine/io/csv/csv_read.h"
#include "engine/live/axis_stream.h"
#include "engine/base/error.h"
#include "engine/io/fbx/fbx_read.h"
#include "engine/io/fbx/fbx_write.h"
#include "engine/io/gltf/gltf_read.h"
#include "engine/io/gltf/gltf_write.h"
#include "engine/io/scene_animation.h"
#include "engine/kinematics/kinematics.h"
#include "engine/kinematics/units.h"
#include "engine/prepare/major_skeleton.h"
#include "engine/synthesize/mix_palette.h"
#include "ui/model/document_fields.h"
#include "ui/model/session_file.h"

namespace mostyle::fuzz {
namespace {

void check(bool ok, const std::string& what) {
  if (!ok) throw std::logic_error("fuzz check failed: " + what);
}

// An InputError as the edges show it: one line that starts with "SOURCE:".
void check_refusal(const InputError& e, const std::string& source) {
  const std::string message = e.what();
  check(message.rfind(source + ":", 0) == 0, "the message names " + source + ": " + message);
  check(message.find_first_of("\r\n") == std::string::npos, "the message is one line: " + message);
}

void check_same_clip(const Clip& a, const Clip& b) {
  check(a.skeleton.joints.size() == b.skeleton.joints.size(), "round trip: joint count");
  for (size_t i = 0; i < a.skeleton.joints.size(); ++i) {
    const Joint& x = a.skeleton.joints[i];
    const Joint& y = b.skeleton.joints[i];
    check(x.name == y.name, "round trip: name of joint " + std::to_string(i));
    check(x.parent == y.parent && x.end_site == y.end_site, "round trip: tree at joint " + std::to_string(i));
    check(x.channels == y.channels && x.first_channel == y.first_channel,
          "round trip: channels of joint " + std::to_string(i));
    // The writer zeroes a root's OFFSET when position channels place it (bvh_write.h).
    const bool moot = x.parent < 0 && !x.channels.empty() &&
                      std::any_of(x.channels.begin(), x.channels.end(), is_position);
    check(moot || x.offset == y.offset, "round trip: OFFSET of joint " + std::to_string(i));
  }
  check(a.skeleton.channel_count == b.skeleton.channel_count, "round trip: channel count");
  check(a.frame_time == b.frame_time, "round trip: frame time");
  check(a.motion.rows() == b.motion.rows() && a.motion.cols() == b.motion.cols() && a.motion == b.motion,
        "round trip: frames");
}

// Every take of a scene sampled; what loads is a consistent clip, written as GLB and read back
// with the same joints. Returns whether any take loaded.
bool sample_takes(const AnimatedScene& scene, const std::string& source) {
  bool any = false;
  for (size_t t = 0; t < scene.takes.size(); ++t) {
    Clip clip;
    try {
      SceneClipOptions o;
      // 512 KB of frames: the seeds' short takes are sampled, Blender's 25 s at 30 fps (580 KB)
      // and 22 s at 120 fps are refused at the limit (a path of its own), so a run tries many
      // inputs, not a few long takes (a 758-frame take's glTF round trip takes 2.7 s under ASan,
      // past libFuzzer's 10 s on a loaded machine).
      o.max_bytes = size_t{512} << 10;
      clip = scene_take_to_clip(scene, static_cast<int>(t), o);
    } catch (const InputError& e) {
      check_refusal(e, source);
      continue;
    }
    any = true;
    const Skeleton& s = clip.skeleton;
    check(clip.frames() >= 1, "a sampled take has a frame");
    check(clip.motion.cols() == s.channel_count, "motion has channel_count columns");
    check(clip.motion.allFinite(), "every sampled value is finite");
    for (size_t i = 0; i < s.joints.size(); ++i) check(s.joints[i].parent < static_cast<int>(i), "parents first");
    const AnimatedScene again = parse_gltf(format_glb(clip, "again"), "again.glb");
    check(again.nodes.size() == s.joints.size() + 1, "round trip: the joints as nodes, and the armature");
    check(again.takes.size() == 1, "round trip: one animation");
  }
  return any;
}

}  // namespace

bool read_gltf(std::string_view bytes) {
  const std::string source = "fuzz.glb";
  try {
    return sample_takes(parse_gltf(bytes, source, "", size_t{64} << 20), source);
  } catch (const InputError& e) {
    check_refusal(e, source);
    return false;
  }
}

bool read_fbx(std::string_view bytes) {
  const std::string source = "fuzz.fbx";
  try {
    return sample_takes(parse_fbx(bytes, source), source);
  } catch (const InputError& e) {
    check_refusal(e, source);
    return false;
  }
}

bool read_bvh(std::string_view bytes) {
  const std::string source = "fuzz.bvh";
  Clip clip;
  try {
    std::vector<std::string> warnings;
    clip = parse_bvh(bytes, source, &warnings);
    for (const std::string& w : warnings) check_refusal(InputError(w), source);
  } catch (const InputError& e) {
    check_refusal(e, source);
    return false;
  }
  const Skeleton& s = clip.skeleton;
  check(clip.motion.cols() == s.channel_count, "motion has channel_count columns");
  check(clip.motion.allFinite(), "every value is finite");
  check(std::isfinite(clip.frame_time) && clip.frame_time > 0, "the frame time is positive");
  int channels = 0;
  for (size_t i = 0; i < s.joints.size(); ++i) {
    const Joint& j = s.joints[i];
    check(j.parent < static_cast<int>(i), "parents come before children");
    check(j.first_channel == channels, "channels are numbered in file order");
    check(j.offset.allFinite(), "offsets are finite");
    channels += static_cast<int>(j.channels.size());
  }
  check(channels == s.channel_count, "channel_count adds up");
  // What loads can be written, and the writer's text reads back as the same clip.
  std::vector<std::string> warnings;
  check_same_clip(clip, parse_bvh(format_bvh(clip), "again.bvh", &warnings));
  check(warnings.empty(), "the written text reads back without warnings");
  return true;
}

bool read_mapping(std::string_view bytes) {
  const std::string source = "fuzz.txt";
  try {
    const MappingOverrides m = parse_mapping_overrides(std::string(bytes), source);
    check(m.entries.size() == m.lines.size(), "one line number per entry");
    for (size_t i = 0; i < m.entries.size(); ++i) {
      check(!m.entries[i].second.empty(), "every entry names a joint");
      check(i == 0 || m.lines[i] > m.lines[i - 1], "entries in line order");
    }
    return true;
  } catch (const InputError& e) {
    check_refusal(e, source);
    return false;
  }
}

bool read_csv(std::string_view bytes) {
  const std::string source = "fuzz.csv";
  try {
    const Eigen::MatrixXd m = parse_csv_matrix(bytes, source);
    check(m.rows() > 0 && m.cols() > 0, "a loaded series has rows and columns");
    check(m.allFinite(), "every value is finite");
    return true;
  } catch (const InputError& e) {
    check_refusal(e, source);
    return false;
  }
}

bool read_job_line(std::string_view bytes) {
  const std::string source = "fuzz.jsonl";
  try {
    const std::vector<std::string> args = cli::parse_job_line(bytes, source, 1);
    check(!args.empty() && args[0] != "batch", "a job is one command, not a batch");
    // The batch summary writes the arguments back as JSON: what was read must be writable.
    (void)nlohmann::json(args).dump();
    return true;
  } catch (const InputError& e) {
    check_refusal(e, source);
    return false;
  }
}

bool read_session(std::string_view bytes) {
  const std::string source = "fuzz.mostyle";
  ui::SessionFile session;
  try {
    session = ui::parse_session(bytes, source);
  } catch (const InputError& e) {
    check_refusal(e, source);
    return false;
  }
  const ui::Document& d = session.document;
  const ui::DocumentControls& c = d.controls;
  auto in_layer_range = [](double w) { return w >= ui::kLayerWeightRange.lo && w <= ui::kLayerWeightRange.hi; };
  for (const ui::TakeLayer& layer : d.layers) {
    check(in_layer_range(layer.weight), "layer weights in the layers' range");
    for (const std::optional<double>& w : layer.component_weights)
      check(!w || in_layer_range(*w), "weights per component in the layers' range");
  }
  check(d.parameters.components >= 1, "at least one component");
  check(d.parameters.sparsity > 0.0 && d.parameters.sparsity <= 1.0, "sparsity in (0, 1]");
  for (double f : c.basic_sparsities) check(f > 0.0 && f <= 1.0, "basic sparsities in (0, 1]");
  check(c.basic_motions >= 0 && c.swap_level >= 0 && (c.swap_level == 0 || c.swap_level < c.basic_motions),
        "the level from B is one of the basic motions");
  check(c.selected_component == -1 && c.dtw_coordinate == 1, "a document keeps the view's own state at defaults");
  for (const std::string& f : d.files) check(!f.empty(), "no empty take");
  check(std::isfinite(session.playback.time_s) && session.playback.time_s >= 0.0, "the playhead is a time");
  check(std::isfinite(session.playback.speed) && session.playback.speed > 0.0f, "the speed is positive");
  if (session.camera) {
    const ui::SessionCamera& cam = *session.camera;
    check(std::isfinite(cam.distance) && cam.distance > 0.0f, "the camera distance is positive");
    check(std::isfinite(cam.yaw) && std::isfinite(cam.pitch) && std::isfinite(cam.fov_y) && cam.fov_y > 0.0f,
          "the camera angles are finite");
    for (float x : cam.target) check(std::isfinite(x), "the camera target is finite");
  }
  // What was read is written, and the text written reads back as the same session.
  const ui::SessionFile again = ui::parse_session(ui::format_session(session, source), source);
  check(again.document == d, "round trip: the document");
  check(again.camera == session.camera, "round trip: the camera");
  check(again.playback.time_s == session.playback.time_s && again.playback.playing == session.playback.playing &&
            again.playback.speed == session.playback.speed && again.playback.loop == session.playback.loop,
        "round trip: the playback");
  return true;
}

namespace {

// The first take of a scene as a clip, within 512 KB of frames (see sample_takes).
Clip first_take(const AnimatedScene& scene) {
  SceneClipOptions o;
  o.max_bytes = size_t{512} << 10;
  return scene_take_to_clip(scene, 0, o);
}

// Whether a clip's numbers are moderate enough that float32 keys keep its joint positions to
// 1e-4 of its extent: rates, offsets, channel values within bounds, names unique.
bool moderate(const Clip& clip) {
  const double fps = clip.fps();
  if (!(fps >= 1e-2 && fps <= 1e5) || clip.motion.cwiseAbs().maxCoeff() > 1e4) return false;
  std::vector<std::string> names;
  for (const Joint& j : clip.skeleton.joints) {
    if (j.offset.cwiseAbs().maxCoeff() > 1e4) return false;
    names.push_back(j.name);
  }
  std::sort(names.begin(), names.end());
  return std::adjacent_find(names.begin(), names.end()) == names.end();
}

// A written file read back: the same joints (End Sites aside, which no key moves) and frames,
// and for a moderate clip the same joint positions. A glTF file states no frame rate: keys
// spaced as no capture is (under 1 or over 1000 per second) are read at 30 per second
// (scene_animation.h default_take_rate), so such a take comes back as long, in other frames.
// back: read from what was written of clip, its lengths `metres` times clip's (glTF is written
// in metres).
void check_read_back(const Clip& clip, const Clip& back, const std::string& what, bool rate_from_keys = false,
                     double metres = 1.0) {
  check(back.skeleton.joint_count_without_end_sites() == clip.skeleton.joint_count_without_end_sites(),
        what + ": the joints");
  if (rate_from_keys && !(clip.fps() >= 1.0 && clip.fps() <= 1000.0)) {
    const double length = (clip.frames() - 1) / clip.fps(), back_length = (back.frames() - 1) / back.fps();
    check(back.fps() == 30.0 && std::abs(back_length - length) <= 1.0 / 30.0 + 1e-9 * length, what + ": the length");
    return;
  }
  check(back.frames() == clip.frames(), what + ": the frames");
  if (!moderate(clip)) return;
  const Eigen::MatrixXd a = metres * joint_positions(clip), b = joint_positions(back);
  const double extent = std::max(metres, a.cwiseAbs().maxCoeff());
  for (size_t i = 0; i < clip.skeleton.joints.size(); ++i) {
    if (clip.skeleton.joints[i].end_site) continue;
    const int j = back.skeleton.find(clip.skeleton.joints[i].name);
    check(j >= 0, what + ": joint " + clip.skeleton.joints[i].name);
    const double d = (a.middleCols(3 * i, 3) - b.middleCols(3 * j, 3)).rowwise().norm().maxCoeff();
    check(d <= 1e-4 * extent, what + ": the positions of " + clip.skeleton.joints[i].name);
  }
}

}  // namespace

bool write_read_back(std::string_view bytes) {
  const bool fbx = bytes.substr(0, 18) == "Kaydara FBX Binary" ||
                   bytes.substr(0, 4096).find("FBXHeaderExtension") != std::string_view::npos;
  const bool gltf = !fbx && (bytes.substr(0, 4) == "glTF" || bytes.substr(0, 1) == "{");
  const std::string source = fbx ? "fuzz.fbx" : gltf ? "fuzz.glb" : "fuzz.bvh";
  Clip clip;
  try {
    if (fbx) clip = first_take(parse_fbx(bytes, source));
    else if (gltf) clip = first_take(parse_gltf(bytes, source, "", size_t{64} << 20));
    else clip = parse_bvh(bytes, source, nullptr);
    // Well within the readers' sampling limit: what is written has a translation and a rotation
    // per joint, so its read-back (up to ten values a joint and frame, counted here) must stay
    // within that limit; a run then tries many inputs rather than a few long ones.
    const size_t read_back = static_cast<size_t>(clip.frames()) * clip.skeleton.joints.size() * 10 * sizeof(double);
    if (static_cast<size_t>(clip.motion.size()) * sizeof(double) > (size_t{128} << 10) || read_back > (size_t{256} << 10))
      return false;
  } catch (const InputError& e) {
    check_refusal(e, source);
    return false;
  }
  // Written FBX: refused only as the writer says (no joints, no frames, a NUL in a name, a
  // rate FBX times cannot hold), else read back by assimp.
  std::string written;
  try {
    written = format_fbx(clip, "again");
  } catch (const InputError& e) {
    check_refusal(e, source);
  }
  if (!written.empty()) {
    try {
      check_read_back(clip, first_take(parse_fbx(written, "again.fbx")), "FBX round trip");
    } catch (const InputError& e) {
      // Values float32 keys cannot hold become infinite: refused on reading, as they should be.
      if (std::string(e.what()).find("more than the limit") == std::string::npos)
        check(!moderate(clip), std::string("a moderate clip's FBX reads back: ") + e.what());
    }
  }
  if (clip.skeleton.joints.empty() || clip.frames() == 0) return true;
  try {
    const double metres = metres_per_unit(clip);
    check_read_back(clip, first_take(parse_gltf(format_glb(clip, "again"), "again.glb")), "glTF round trip",
                    /*rate_from_keys=*/true, metres > 0.0 ? metres : 1.0);
  } catch (const InputError& e) {
    // Names glTF cannot hold are refused by the writer, in one sentence.
    // So are read-backs sampled past the readers' memory limit (a take whose key times the
    // reader samples at a finer rate than the take's own), in one sentence.
    const bool names_refused = std::string(e.what()).find("is not UTF-8 text") != std::string::npos ||
                               std::string(e.what()).find("more than the limit") != std::string::npos;
    if (names_refused) check(std::string(e.what()).find_first_of("\r\n") == std::string::npos, "one line");
    else check(!moderate(clip), std::string("a moderate clip's GLB reads back: ") + e.what());
  }
  return true;
}

namespace {

// The lines the splitter gives for `bytes` cut into chunks of `chunk` bytes (0: whole).
std::vector<std::string> split_axis_lines(std::string_view bytes, size_t chunk, size_t max_line,
                                          long long* dropped) {
  AxisLineSplitter splitter(max_line);
  std::vector<std::string> lines;
  const size_t step = chunk == 0 ? std::max<size_t>(1, bytes.size()) : chunk;
  for (size_t at = 0; at < bytes.size(); at += step) {
    std::string_view rest = bytes.substr(at, step), line;
    while (splitter.next(&rest, &line)) {
      check(line.size() <= max_line, "a line within the bound");
      check(line.find('\n') == std::string_view::npos, "a line holds no line end");
      lines.emplace_back(line);
    }
    check(rest.empty(), "the splitter takes every byte");
  }
  *dropped = splitter.dropped();
  return lines;
}

}  // namespace

bool read_axis_stream(std::string_view bytes) {
  if (bytes.empty()) return false;
  const unsigned char first = static_cast<unsigned char>(bytes[0]);
  const int channels = 1 + first % 16;
  const size_t chunk = first / 16;  // 0 (whole) to 15 bytes
  const size_t max_line = 256;
  bytes.remove_prefix(1);
  long long dropped = 0, dropped_whole = 0;
  const std::vector<std::string> lines = split_axis_lines(bytes, chunk, max_line, &dropped);
  check(lines == split_axis_lines(bytes, 0, max_line, &dropped_whole) && dropped == dropped_whole,
        "the same lines however the bytes are cut");
  bool any = false;
  AxisFrame frame, again;
  std::string reason, written;
  for (const std::string& line : lines) {
    const AxisLineStatus status = parse_axis_line(line, channels, &frame, &reason);
    if (status == AxisLineStatus::kMalformed) {
      check(!reason.empty(), "a refusal says why");
      for (char c : reason) check(c >= 0x20 && c < 0x7f, "a refusal is printable text on one line: " + reason);
      continue;
    }
    check(status == AxisLineStatus::kOk, "the splitter gives no blank line");
    any = true;
    check(static_cast<int>(frame.values.size()) == channels, "a frame has the channels' values");
    check(frame.reference.empty() || frame.reference.size() == kAxisReferenceValues, "a reference has 6 values");
    check(!frame.avatar_name.empty() && frame.avatar_name.find_first_of(" \t\r\n") == std::string::npos,
          "the avatar name is one token");
    written.clear();
    append_axis_line(&written, frame.avatar_index, frame.avatar_name, frame.reference.data(),
                     static_cast<int>(frame.reference.size()), frame.values.data(), channels);
    check(parse_axis_line(written, channels, &again, &reason) == AxisLineStatus::kOk, "a written line reads back");
    check(again.avatar_index == frame.avatar_index && again.avatar_name == frame.avatar_name &&
              again.reference == frame.reference,
          "round trip: avatar and reference");
    for (size_t i = 0; i < frame.values.size(); ++i) {
      check(std::isfinite(frame.values[i]), "every value is finite");
      check(std::abs(again.values[i] - frame.values[i]) <= 1e-6 * std::abs(frame.values[i]), "round trip: values");
    }
  }
  return any;
}

const std::vector<std::string>& target_names() {
  static const std::vector<std::string> names = {"bvh", "mapping", "csv", "job_line", "session", "gltf", "fbx",
                                                 "write", "axis"};
  return names;
}

bool read_as(const std::string& target, std::string_view bytes) {
  if (target == "bvh") return read_bvh(bytes);
  if (target == "mapping") return read_mapping(bytes);
  if (target == "csv") return read_csv(bytes);
  if (target == "job_line") return read_job_line(bytes);
  if (target == "session") return read_session(bytes);
  if (target == "gltf") return read_gltf(bytes);
  if (target == "fbx") return read_fbx(bytes);
  if (target == "write") return write_read_back(bytes);
  if (target == "axis") return read_axis_stream(bytes);
  throw std::logic_error("no fuzz target named " + target);
}

}  // namespace mostyle::fuzz
