#pragma once
// Pieces the style-pipeline subcommands (align, blend, mix, transfer) share: the alignment
// flags, the clean-up flags, body-part entries and the report's JSON parts.
#include <CLI/CLI.hpp>
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "app/cli/synthesis_request.h"
#include "engine/decompose/body_parts.h"
#include "engine/export/channel_layout.h"
#include "engine/prepare/major_skeleton.h"
#include "engine/post/loop.h"
#include "engine/synthesize/mix_measures.h"
#include "engine/synthesize/mix_palette.h"

namespace mostyle::cli {

// --fps, --time-base, --dtw, --align-on, --max-slope, --closed-ends, --band, bound to `align`.
void add_align_options(CLI::App* cmd, AlignOptions& align);

// --channels as-source|rotations, bound to `channels` (unset: rotations where the reference's
// position channels below the root keep one value, export/channel_layout.h).
void add_channels_option(CLI::App* cmd, std::string& channels);

// A mapping file's overrides (empty path: none).
MappingOverrides load_mapping(const std::string& path);

// Numbers separated by commas, each a decimal or a fraction ("0.2,1/3,...", base/numbers.h);
// `flag` names the option in the error. Throws InputError on an entry that is neither.
std::vector<double> parse_numbers(const std::string& list, const std::string& flag);

// Weights keyed in time as typed: "T:v1,v2,...;T:..." (T in seconds of the output), each key with
// `count` numbers; with count 1 the keys may also be separated by commas ("0:0,10:1"). `flag`
// names the option in errors. Throws InputError on a key that is not T:numbers or has another
// count; the times' order is checked by MixParams::Validate.
std::vector<std::pair<double, std::vector<double>>> parse_keys(const std::string& text, const std::string& flag,
                                                               size_t count);
// The keys as a report lists them: [{"seconds": T, "weights": [...]}, ...].
Json keys_json(const WeightKeys& keys);

// A few lines for a person (what was made, how long, how well, where it went) from a blend's,
// mix's or transfer's report, for stdout when no --report is asked for.
std::string report_summary(const Json& report, const std::string& out, const std::string& positions_out);

// "PART:v1,v2,..." entries (repeated) split into a part and its numbers; `flag` names the option
// in errors. Each entry needs `count` numbers (0: any number). Throws InputError.
std::vector<std::pair<BodyPart, std::vector<double>>> parse_part_entries(const std::vector<std::string>& entries,
                                                                         const std::string& flag, size_t count);

Json range_json(int first, int last, double fps);
// Take `take`'s alignment onto the reference (take 0): what it aligned on, the matched ranges,
// its quality.
Json alignment_json(const PreparedTakes& p, int take);
// A take's cycles (engine/align/cycles.h) at `fps`: {"kind", "foot" and "strike_phase" (gait),
// "period_s", "loop_frames" (a loop clip), "reason" (why no cycles or no gait cycles, when
// there is one), "cycles": [{"start", "end", "seconds"}]} with start and end in frames at fps.
Json cycles_json(const TakeCycles& cycles, double fps);
// One line: "gait, 14 cycles (left foot), median 0.95 s, 87% of the take", with the loop, its
// strike and why there is no gait when the take has them; "none (REASON)".
std::string cycles_summary(const TakeCycles& cycles, double fps, int frames);
Json component_joints_json(const std::vector<ComponentJoints>& parts, const std::vector<std::string>& names);
Json component_regions_json(const std::vector<ComponentJoints>& parts);
Json vector_json(const Eigen::VectorXd& v);
// How a take's major joints were found: {"how": sentence, "joints": [{"role", "joint" (the
// skeleton's name, null where none), "found_by" ("name", "structure", "mapping file", "none")}]}.
Json major_joints_json(const MajorMapping& mapping, const Skeleton& skeleton);
Json loop_json(const LoopCut& loop, double fps);
// A result's measures (engine/synthesize/mix_measures.h) as the report gives them:
// "limb_length_max_error"; "foot_sliding", how fast the output's planted feet move ("raw" before
// the foot lock, "cleaned" after it, "inputs" the takes' own weighted as mixed, file units per
// second; the same as fractions of "body_height" per second ("raw_of_height", ...); "ratio"
// cleaned over inputs, null when the inputs' feet never move); "fastest_joint", how fast its
// fastest joint moves ("result", "inputs" the fastest of the takes mixed, "ratio" between them,
// null for still takes). Set in `report`.
void add_result_measures(const MixMeasures& measures, Json& report);

}  // namespace mostyle::cli
