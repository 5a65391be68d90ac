#pragma once
// The readers of outside input as the fuzz targets (tests/fuzz/*_fuzz.cpp) and the regression
// test (tests/fuzz/regressions_test.cpp) call them: bytes in, and a check of what every caller
// relies on. A file that loads is consistent (and, for BVH, is written and read back the same);
// one that is refused gives one InputError line naming the source. A session file that loads is
// in range, and is written and read back the same.
#include <string>
#include <string_view>
#include <vector>

namespace mostyle::fuzz {

// Each returns true when `bytes` loaded and false when the reader refused them with InputError.
// A broken check throws std::logic_error (std::terminate in a fuzz target: a reported crash);
// any other exception escapes. No file is touched.
bool read_bvh(std::string_view bytes);       // parse_bvh (engine/io/bvh/bvh_read.h), as "fuzz.bvh"
bool read_mapping(std::string_view bytes);   // parse_mapping_overrides (engine/prepare/major_skeleton.h)
bool read_csv(std::string_view bytes);       // parse_csv_matrix (engine/io/csv/csv_read.h)
bool read_job_line(std::string_view bytes);  // parse_job_line (app/batch/job_line.h)
bool read_session(std::string_view bytes);   // parse_session (ui/model/session_file.h), as "fuzz.mostyle"
// parse_gltf (engine/io/gltf/gltf_read.h) as "fuzz.glb", then every take sampled into a clip
// (scene_animation.h, 2 MB limit), written as GLB and read back with the same skeleton.
bool read_gltf(std::string_view bytes);
// parse_fbx (engine/io/fbx/fbx_read.h) as "fuzz.fbx", then every take sampled as for glTF.
bool read_fbx(std::string_view bytes);

// Any take (FBX when the bytes start as binary FBX or hold FBXHeaderExtension near the start,
// glTF when they start with "glTF" or '{', else BVH) read into a clip, written as FBX
// (engine/io/fbx/fbx_write.h) and as GLB, and each read back by our readers: with the same joints
// and frames, and, for moderate values, the same joint positions. Returns whether the take
// loaded.
bool write_read_back(std::string_view bytes);

// A TCP byte stream of Axis Neuron BVH broadcasting lines (engine/live/axis_stream.h): the first
// byte picks the channel count (1 to 16) and the size of the chunks the rest is cut into; each
// line the splitter gives is parsed. The lines are the same however the bytes are cut, none
// over the bound; a frame read is finite and as many values as the channels (and a reference of
// 6 or none), and written and read back the same (within 1e-6); a refusal is one printable
// clause. Returns whether any line was a frame.
bool read_axis_stream(std::string_view bytes);

// The targets by the name of their folder in tests/fuzz/regressions/: "bvh", "mapping", "csv",
// "job_line", "session", "gltf", "fbx", "write", "axis".
const std::vector<std::string>& target_names();
bool read_as(const std::string& target, std::string_view bytes);

}  // namespace mostyle::fuzz
