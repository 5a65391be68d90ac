#pragma once
// Small pieces every mostyle-cli subcommand shares: numbers, position CSVs, loading.
#include <CLI/CLI.hpp>
#include <Eigen/Core>
#include <string>
#include <vector>

#include "engine/io/bvh/bvh_read.h"
#include "engine/base/clip.h"
#include "engine/io/motion_file.h"

namespace mostyle::cli {

// Shortest text that reads back as the same double.
std::string number(double v);

// Writes `content` atomically; throws InputError on failure.
void write_output(const std::string& path, const std::string& content);

// CSV "frame,joint,x,y,z", one row per joint per frame. positions: F x 3J; joints[i] is the
// column triple of names[i].
std::string positions_csv(const Eigen::MatrixXd& positions, const std::vector<int>& joints,
                          const std::vector<std::string>& names);

// The memory limit of a reader of outside input from the environment: MOSTYLE_MAX_MEMORY_MB,
// when set, bounds the memory one file's values may need (default 4096). Throws InputError when
// it is not a whole number of megabytes from 1 up (engine/base/memory_limit.h).
size_t memory_limit_from_environment();
// The BVH reader's options with that limit.
BvhReadOptions bvh_read_options_from_environment();
// The same limit for any motion file (engine/io/motion_file.h).
MotionReadOptions motion_read_options_from_environment();

// A check for an option naming a motion file to write: it must end in one of the formats
// written (.bvh, .glb, .gltf, case-insensitive), never another format's name over BVH text; a
// parse error (exit status 2) names them otherwise.
const CLI::Validator& written_motion_format();

// Reads a take (engine/io/motion_file.h: BVH, FBX, glTF; `path` may be FILE#ANIMATION), with
// the memory limit above, `take` (--take; "" for FILE#ANIMATION's or the first) and `fps` (the
// sampling rate of FBX and glTF keys; 0 for the file's own). Prints the reader's warnings to
// stderr as "mostyle: warning: ..." and its notes (which animation of several it took) as
// "mostyle: note: ...".
Clip load_clip(const std::string& path, const std::string& take = "", double fps = 0.0);

}  // namespace mostyle::cli
