#include "app/cli/synthesis_request.h"

#include <chrono>
#include <cmath>

#include "app/cli/cli_common.h"
#include "app/cli/cli_pipeline_common.h"
#include "engine/align/warp_position.h"
#include "engine/base/clock.h"
#include "engine/base/error.h"
#include "engine/export/export_frames.h"
#include "engine/kinematics/units.h"

namespace mostyle::cli {
namespace {

using Clock = std::chrono::steady_clock;

void tell(const SynthesisOptions& options, const std::string& line) {
  if (options.message) options.message(line);
}

std::shared_ptr<const Clip> read_take(const TakeSource& take, const SynthesisOptions& options) {
  if (take.clip) return take.clip;
  std::vector<std::string> warnings, notes;
  auto clip = std::make_shared<const Clip>(read_motion_file(take.file, &warnings, motion_read_options_from_environment(), &notes));
  for (const std::string& w : warnings) tell(options, "warning: " + w);
  for (const std::string& n : notes) tell(options, "note: " + n);
  return clip;
}

// Reads, prepares and decomposes the takes; the alignment's warnings go to the message sink.
// Mapping files name the reference's joints and the second take's.
PreparedSynthesis prepare(const std::vector<TakeSource>& takes, const SynthesisOptions& options,
                          const DecomposeParams& dp, const std::string& mapping_a = "",
                          const std::string& mapping_b = "") {
  PreparedSynthesis p;
  p.takes = takes;
  p.align = options.align;
  p.decompose = dp;
  PrepareOptions o = options.align.options();
  const auto t0 = Clock::now();
  std::vector<std::shared_ptr<const Clip>> clips;
  for (const TakeSource& t : takes) clips.push_back(read_take(t, options));
  p.times.load_ms = ms_since(t0);
  o.mapping_a = load_mapping(mapping_a);
  o.mapping_b = load_mapping(mapping_b);
  p.prepared = prepare_takes(clips, o, nullptr, &p.times);
  for (const PreparedTake& t : p.prepared->takes)
    for (const std::string& w : t.alignment.warnings) tell(options, "warning: " + w);
  p.decomposition = decompose_takes(*p.prepared, dp, nullptr, &p.times);
  return p;
}

// The layers a result was mixed with (engine/synthesize/mix_layers.h), as the report lists them:
// "layers", each {"take", "weight"} and "component_weights" where it has them, and "additive",
// each {"take", "from", "strength"} and its strengths per component. The takes by their index
// in the report's "takes".
Json layers_json(const MixLayers& layers) {
  Json normal = Json::array(), additive = Json::array();
  for (const MixLayer& l : layers.layers) {
    Json j = {{"take", l.take}, {"weight", l.weight}};
    if (!l.component_weights.empty()) j["component_weights"] = l.component_weights;
    normal.push_back(j);
  }
  for (const AdditiveLayer& l : layers.additive) {
    Json j = {{"take", l.take}, {"from", l.from}, {"strength", l.weight}};
    if (!l.component_weights.empty()) j["component_strengths"] = l.component_weights;
    additive.push_back(j);
  }
  return {{"layers", normal}, {"additive", additive}};
}

// The fields every blend, mix and transfer reports, after the command's own in `r`.
void add_report_fields(const SynthesisResult& s, const std::vector<TakeSource>& takes, const SynthesisOptions& options,
                       const MixParams& mp, StageTimes times, Json& r) {
  const PreparedTakes& palette = *s.prepared;
  const Decomposed& d = *s.decomposition;
  const MixResult& result = s.mix;
  const Eigen::MatrixXd& world = result.motion.world;
  r["frames"] = world.rows();
  r["fps"] = palette.fps;
  // A loop lasts all its frames (the next repeat follows its last); a clip, first frame to last.
  r["duration_s"] = options.loop ? world.rows() / palette.fps : motion_length_s(world.rows(), palette.fps);
  r["components"] = options.components;
  r["sparsity"] = options.sparsity;
  r["joints"] = s.joints;
  r["timing"] = options.timing;
  r["residual"] = mp.residual;
  Json list = Json::array();
  const std::vector<double> weights = take_weights(mp.layers, palette.size());
  const MixMeasures measures = mix_measures(palette, &d, &result);
  for (int i = 0; i < palette.size(); ++i) {
    const size_t n = static_cast<size_t>(i);
    const PreparedTake& take = palette.takes[n];
    Json t;
    t["file"] = takes[n].file;
    t["weight"] = weights[n];
    t["major_joints"] = major_joints_json(take.mapping, take.clip->skeleton);
    t["reconstruction_rmse"] = *measures.takes[n].fit_error;
    t["foot_sliding"] = measures.takes[n].planted_speed;
    t["fastest_joint"] = measures.takes[n].fastest_joint;
    if (i > 0) t["alignment"] = alignment_json(palette, i);
    // Its own file's frames at the working rate (null where a take registered by cycles gives
    // its posture only), and which of its cycles each output frame shows (-1: none).
    t["source_frames"] = vector_json(frames_in_take(take, result.sources.col(i)));
    const Eigen::VectorXi shown = cycles_shown(take, result.sources.col(i));
    t["source_cycles"] = std::vector<int>(shown.data(), shown.data() + shown.size());
    const CycleRegistration& registration = take.registration;
    t["time_base"] = take.alignment.by_structure ? "structure"
                     : registration.empty()      ? "whole"
                     : registration.posture_only() ? "posture"
                                                   : "cycles";
    t["structure"] = action_structure_summary(take.cycles, palette.fps);
    list.push_back(t);
  }
  r["takes"] = list;
  r["mixed_as"] = layers_json(mp.layers);
  r["common_timeline"] = {{"samples", palette.samples()},
                          {"reference_first", palette.timeline.frames[0][0]},
                          {"reference_last", palette.timeline.frames[0][palette.samples() - 1]}};
  if (options.loop) r["loop"] = loop_json(result.motion.loop, palette.fps);
  r["iterations"] = d.iterations;
  r["local"] = d.params.local && d.shared() != nullptr;
  r["component_joints"] = component_joints_json(d.component_joints, s.joints);
  r["component_regions"] = component_regions_json(d.component_joints);
  if (s.solved) {
    r["export_fit"] = {{"max", s.clip.fit.max}, {"mean", s.clip.fit.mean}};
    r["channels"] = channel_layout_name(options.channels.empty() ? default_channel_layout(*palette.takes.front().clip)
                                                                 : parse_channel_layout(options.channels));
  }
  r["foot_lock"] = mp.finish.foot_lock;
  add_result_measures(measures, r);
  r["skeleton_height"] = guess_units(*palette.takes.front().clip).height;
  r["timings_ms"] = {{"load", times.load_ms},         {"preprocess", times.preprocess_ms},
                     {"dtw", times.dtw_ms},           {"decompose", times.decompose_ms},
                     {"synthesize", times.synthesize_ms}, {"postprocess", times.postprocess_ms},
                     {"export", times.export_ms}};
}

// Mixes, solves the clip when asked and fills the report. `r` already holds the command's own
// fields; `words` adds the fields only it reports, once the mix is made.
SynthesisResult synthesize(const PreparedSynthesis& p, const SynthesisOptions& options, const MixParams& mp,
                           MixScratch& scratch, Json r,
                           const std::function<void(const SynthesisResult&, Json&)>& words = {}) {
  const std::vector<TakeSource>& takes = p.takes;
  SynthesisResult s;
  s.prepared = p.prepared;
  s.decomposition = p.decomposition;
  const PreparedTakes& palette = *p.prepared;
  StageTimes times = p.times;
  mix_palette(palette, *p.decomposition, mp, scratch, s.mix, &times);
  s.joints = palette.takes.front().names;
  if (!options.out.empty() || options.solve_clip) {
    const Clip& reference = *palette.takes.front().clip;
    const ChannelLayout layout =
        options.channels.empty() ? default_channel_layout(reference) : parse_channel_layout(options.channels);
    const auto t_export = Clock::now();
    s.clip = solve_export_in_layout(reference, export_joints(palette), s.mix.motion.world,
                                    source_frames_in_clip(palette, s.mix), palette.fps, layout);
    s.solved = true;
    times.export_ms = ms_since(t_export);
  }
  add_report_fields(s, takes, options, mp, times, r);
  if (words) words(s, r);
  s.report = std::move(r);
  return s;
}

// A blend's alpha is B's weight and 1 - alpha is A's: refused outside the range mix allows a
// weight (kMinMixWeight to kMaxMixWeight, symmetric about 1/2, so A's weight is in it too).
void check_alpha(double alpha, const std::string& flag) {
  if (!(alpha >= kMinMixWeight && alpha <= kMaxMixWeight))
    throw InputError("expected " + flag + " from " + number(kMinMixWeight) + " to " + number(kMaxMixWeight) +
                     " (B's weight; A's is 1 - alpha), found " + number(alpha));
}

// The alphas given per body part (--part-alpha, "legs:0.2,arms:0.8" or repeated), each checked.
std::vector<std::pair<BodyPart, double>> part_alphas(const std::vector<std::string>& part_alpha) {
  std::vector<std::string> entries;
  for (const std::string& e : part_alpha)
    for (size_t begin = 0; begin <= e.size();) {
      const size_t comma = std::min(e.find(',', begin), e.size());
      entries.push_back(e.substr(begin, comma - begin));
      begin = comma + 1;
    }
  std::vector<std::pair<BodyPart, double>> given;
  for (const auto& [part, values] : parse_part_entries(entries, "--part-alpha", 1)) {
    check_alpha(values[0], std::string("--part-alpha ") + body_part_name(part));
    given.emplace_back(part, values[0]);
  }
  return given;
}

// A blend's alphas per component (--component-alpha, or --part-alpha's for the parts given and
// --alpha for the rest), in shared mode; none otherwise (paper mode blends the whole body).
std::vector<double> component_alphas(const BlendRequest& request, const std::vector<std::pair<BodyPart, double>>& given,
                                     const Decomposed& d) {
  if (d.shared() == nullptr) return {};
  if (!given.empty()) return weights_for_parts(given, d.component_joints, request.alpha);
  if (!request.component_alpha.empty() && static_cast<int>(request.component_alpha.size()) != d.components())
    throw InputError("expected " + std::to_string(d.components()) + " component alphas, found " +
                     std::to_string(request.component_alpha.size()));
  return request.component_alpha;
}

// A blend's two layers: A at 1 - alpha, B at alpha, per component (1 - alpha_c, alpha_c) when
// `alphas` has one per component.
MixLayers blend_layers(double alpha, const std::vector<double>& alphas) {
  MixLayers layers = take_layers({1.0 - alpha, alpha});
  for (double a : alphas) {
    layers.layers[0].component_weights.push_back(1.0 - a);
    layers.layers[1].component_weights.push_back(a);
  }
  return layers;
}

// A's and B's words in a blend's report: the alignment per output frame, each take's fit and sliding.
void add_pair_words(const PreparedTakes& prepared, const Decomposed& d, const MixResult& result, Json& report) {
  const Alignment& al = prepared.takes[1].alignment;
  report["dtw"] = {{"cost", al.cost}, {"path_length", al.path.size()}};
  Json alignment = alignment_json(prepared, 1);
  // Per output frame: where in A and B it is, how well they match there, the warp's slope.
  Eigen::VectorXd ratio(result.sample.size()), slope(result.sample.size());
  for (Eigen::Index k = 0; k < result.sample.size(); ++k) {
    const Eigen::Index u = std::lround(warp_position(al.warp, prepared.timeline, 1, result.sample[k]));
    ratio[k] = al.cost_ratio[u];
    slope[k] = al.slope[u];
  }
  alignment["per_frame"] = {{"source_a", vector_json(result.sources.col(0))},
                            {"source_b", vector_json(result.sources.col(1))},
                            {"cost_ratio", vector_json(ratio)},
                            {"slope", vector_json(slope)}};
  report["alignment"] = alignment;
  const MixMeasures measures = mix_measures(prepared, &d, nullptr);
  report["reconstruction_rmse"] = {{"a", *measures.takes[0].fit_error}, {"b", *measures.takes[1].fit_error}};
  report["component_nonzero_fraction"] = {{"a", d.nonzero[0]}, {"b", d.nonzero[1]}};
  report["foot_sliding"]["a"] = measures.takes[0].planted_speed;
  report["foot_sliding"]["b"] = measures.takes[1].planted_speed;
}

// One strength per style (--strength, comma separated or repeated; default 1 each).
std::vector<double> transfer_strengths(const TransferRequest& request) {
  const size_t styles = request.styles.size();
  std::vector<double> strengths;
  for (const std::string& s : request.strengths)
    for (double v : parse_numbers(s, "--strength")) strengths.push_back(v);
  if (request.strengths.empty()) strengths.assign(styles, 1.0);
  if (strengths.size() != styles)
    throw InputError("expected " + std::to_string(styles) + " strengths, one per --style, found " +
                     std::to_string(strengths.size()));
  return strengths;
}

}  // namespace

PrepareOptions AlignOptions::options() const {
  PrepareOptions o;
  o.fps = fps;
  o.align.method = parse_dtw_method(dtw);
  o.align.time_base = parse_time_base(time_base);
  o.align.on = parse_align_on(align_on);
  o.align.band = band;
  o.align.slope.max_slope = max_slope;
  o.align.slope.open_ends = !closed_ends;
  o.Validate();
  return o;
}

DecomposeParams SynthesisOptions::decompose_params() const {
  DecomposeParams dp;
  dp.components = components;
  dp.sparsity = sparsity;
  dp.max_iterations = iterations;
  dp.local = !no_local;
  return dp;
}

void SynthesisOptions::set(MixParams& mp) const {
  mp.reference_timing = timing != timing_words.mixed;
  mp.residual = !components_only;
  mp.finish.limb_lengths = !no_limb_constraint;
  mp.finish.foot_lock = !no_foot_lock;
  mp.finish.loop = loop;
}

void SynthesisOptions::Validate() const {
  if (timing != timing_words.mixed && timing != timing_words.reference)
    throw InputError("expected --timing " + std::string(timing_words.mixed) + " or " + timing_words.reference +
                     ", found '" + timing + "'");
  if (!channels.empty()) parse_channel_layout(channels);
}

SynthesisResult blend_takes(const BlendRequest& request) {
  const SynthesisOptions& options = request.options;
  options.Validate();
  if (request.mode != "shared" && request.mode != "paper")
    throw InputError("expected --mode shared or paper, found '" + request.mode + "'");
  DecomposeParams dp = options.decompose_params();
  dp.mode = request.mode == "paper" ? DecompositionMode::kPaper : DecompositionMode::kShared;
  dp.basic_motions = request.basic;
  dp.basic_sparsities = request.basic_sparsities;
  if (!request.part_alpha.empty()) {
    if (!request.component_alpha.empty()) throw InputError("give --part-alpha or --component-alpha, not both");
    if (dp.mode != DecompositionMode::kShared) throw InputError("--part-alpha needs shared mode (--mode shared)");
  }
  // Every alpha is checked before the files are read.
  check_alpha(request.alpha, "--alpha");
  for (double a : request.component_alpha) check_alpha(a, "--component-alpha");
  const std::vector<std::pair<BodyPart, double>> given = part_alphas(request.part_alpha);
  const auto keys = parse_keys(request.alpha_at, "--alpha-at", 1);
  for (const auto& key : keys) check_alpha(key.second[0], "--alpha-at");
  const std::vector<TakeSource> takes{request.a, request.b};
  const PreparedSynthesis p = prepare(takes, options, dp, request.mapping_a, request.mapping_b);
  const Decomposed& d = *p.decomposition;
  MixParams mp;
  mp.layers = blend_layers(request.alpha, component_alphas(request, given, d));
  mp.swap_level = request.swap;
  for (const auto& key : keys) mp.keys.push_back({key.first, {1.0 - key.second[0], key.second[0]}});
  options.set(mp);
  Json r;
  r["command"] = "blend";
  r["a"] = request.a.file;
  r["b"] = request.b.file;
  r["alpha"] = request.alpha;
  if (!mp.keys.empty()) r["keys"] = keys_json(mp.keys);
  r["mode"] = request.mode;
  if (request.basic > 0) {
    r["basic_motions"] = request.basic;
    r["swap"] = request.swap;
  }
  MixScratch scratch;
  return synthesize(p, options, mp, scratch, r, [&](const SynthesisResult& s, Json& report) {
    add_pair_words(*s.prepared, *s.decomposition, s.mix, report);
  });
}

namespace {

// A mix's weights, read from the request and checked before any file is read.
struct MixPlan {
  MixParams params;  // the layers, keys and clean-up; per-part weights are set once decomposed
  std::vector<double> typed, weights;  // as typed, and summing to 1
  std::vector<std::pair<BodyPart, std::vector<double>>> parts;
};

MixPlan mix_plan(const MixRequest& request) {
  const SynthesisOptions& options = request.options;
  options.Validate();
  const size_t n = request.takes.size();
  if (n < 2 || n > static_cast<size_t>(kMaxPaletteTakes))
    throw InputError("mix takes from 2 to " + std::to_string(kMaxPaletteTakes) + " BVH files, found " +
                     std::to_string(n));
  MixPlan w;
  MixParams& mp = w.params;
  w.typed =
      request.weights.empty() ? std::vector<double>(n, 1.0 / double(n)) : parse_numbers(request.weights, "--weights");
  w.weights = normalized_weights(w.typed);
  for (const auto& [seconds, weights] : parse_keys(request.weights_at, "--weights-at", n))
    mp.keys.push_back({seconds, normalized_weights(weights)});
  if (!mp.keys.empty() && !request.part_weights.empty())
    throw InputError("give --weights-at or --part-weights, not both: keys in time mix the whole body");
  w.parts = parse_part_entries(request.part_weights, "--part-weights", n);
  for (auto& entry : w.parts) entry.second = normalized_weights(entry.second);
  if (w.weights.size() != n)
    throw InputError("expected " + std::to_string(n) + " weights, one per take, found " +
                     std::to_string(w.weights.size()));
  mp.layers = take_layers(w.weights);
  mp.Validate(static_cast<int>(n), 0);
  for (const auto& [part, weights] : w.parts) {
    MixParams check = mp;
    check.layers = take_layers(weights);
    try {
      check.Validate(static_cast<int>(n), 0);
    } catch (const InputError& e) {
      throw InputError(std::string("--part-weights ") + body_part_name(part) + ": " + e.what());
    }
  }
  options.set(mp);
  return w;
}

// Body-part entries as the report lists them: {"legs": [...], ...}.
Json parts_json(const std::vector<std::pair<BodyPart, std::vector<double>>>& entries) {
  Json parts = Json::object();
  for (const auto& [part, values] : entries) parts[body_part_name(part)] = values;
  return parts;
}

SynthesisResult mix_with(const PreparedSynthesis& p, const MixRequest& request, MixPlan w, MixScratch& scratch) {
  MixParams& mp = w.params;
  if (!w.parts.empty()) mp.layers = take_layers(w.weights, part_weights(w.parts, p.decomposition->component_joints, w.weights));
  Json r;
  r["command"] = "mix";
  r["weights"] = w.weights;
  r["weights_typed"] = w.typed;
  if (!mp.keys.empty()) r["keys"] = keys_json(mp.keys);
  if (!w.parts.empty()) r["part_weights"] = parts_json(w.parts);
  return synthesize(p, request.options, mp, scratch, r);
}

// A prepared request's takes and options against the request it is asked to mix: the same
// number of takes, aligned and decomposed alike, else the mix would not be the request's.
void check_prepared_for(const PreparedSynthesis& p, size_t takes, const SynthesisOptions& options,
                        const DecomposeParams& dp) {
  const AlignOptions& a = p.align;
  const AlignOptions& b = options.align;
  const bool same_align = a.fps == b.fps && a.band == b.band && a.time_base == b.time_base && a.dtw == b.dtw &&
                          a.align_on == b.align_on && a.max_slope == b.max_slope && a.closed_ends == b.closed_ends;
  const bool same_decompose = p.decompose.components == dp.components && p.decompose.sparsity == dp.sparsity &&
                              p.decompose.max_iterations == dp.max_iterations && p.decompose.local == dp.local &&
                              p.decompose.mode == dp.mode;
  if (p.takes.size() != takes)
    throw InputError("the takes were prepared as " + std::to_string(p.takes.size()) + " takes, the request has " +
                     std::to_string(takes));
  if (!same_align || !same_decompose)
    throw InputError("the takes were prepared with other alignment or decomposition options: prepare them again");
}

}  // namespace

SynthesisResult mix_takes(const MixRequest& request) {
  MixPlan w = mix_plan(request);
  MixScratch scratch;
  return mix_with(prepare(request.takes, request.options, request.options.decompose_params()), request, std::move(w),
                  scratch);
}

PreparedSynthesis prepare_mix(const MixRequest& request) {
  mix_plan(request);
  return prepare(request.takes, request.options, request.options.decompose_params());
}

SynthesisResult mix_prepared(const PreparedSynthesis& prepared, const MixRequest& request, MixScratch& scratch) {
  MixPlan w = mix_plan(request);
  check_prepared_for(prepared, request.takes.size(), request.options, request.options.decompose_params());
  return mix_with(prepared, request, std::move(w), scratch);
}

namespace {

// A transfer's takes and weights, read from the request and checked before any file is read.
struct TransferPlan {
  std::vector<TakeSource> takes;  // the content, the neutral when given, the styles
  TransferNeutral neutral = TransferNeutral::kContent;
  std::vector<double> strengths;
  MixParams params;
  std::vector<std::pair<BodyPart, std::vector<double>>> given;  // strengths per part
};

TransferPlan transfer_plan(const TransferRequest& request) {
  const SynthesisOptions& options = request.options;
  options.Validate();
  if (request.styles.empty()) throw InputError("transfer needs a style take (--style)");
  const size_t styles = request.styles.size();
  TransferPlan w;
  w.strengths = transfer_strengths(request);
  // The takes: the content, the neutral when given, the styles. Without a neutral the content
  // is its own: the same mix, on one take fewer, with the content's weight 1 - sum s.
  const bool has_neutral = !request.neutral.file.empty() || request.neutral.clip;
  w.neutral = has_neutral ? TransferNeutral::kTake : TransferNeutral::kContent;
  w.takes = {request.content};
  if (w.neutral == TransferNeutral::kTake) w.takes.push_back(request.neutral);
  w.takes.insert(w.takes.end(), request.styles.begin(), request.styles.end());
  if (w.takes.size() > static_cast<size_t>(kMaxPaletteTakes))
    throw InputError("transfer takes at most " + std::to_string(kMaxPaletteTakes - (w.takes.size() - styles)) +
                     " styles");
  MixParams& mp = w.params;
  // The content's layer at 1, each style added from the neutral (or the content) at its strength.
  mp.layers = transfer_layers(w.strengths, w.neutral);
  mp.min_weight = transfer_min_weight(static_cast<int>(styles));
  mp.max_weight = transfer_max_weight(static_cast<int>(styles));
  mp.feet_of_reference = true;
  mp.reference_cycles = true;
  for (const auto& [seconds, s] : parse_keys(request.strength_at, "--strength-at", styles))
    mp.keys.push_back({seconds, transfer_weights(s, w.neutral)});
  if (!mp.keys.empty() && !request.part_strengths.empty())
    throw InputError("give --strength-at or --part-strength, not both: keys in time style the whole body");
  w.given = parse_part_entries(request.part_strengths, "--part-strength", styles);
  for (const auto& entry : w.given) transfer_weights(entry.second, w.neutral);  // each checked before any file is read
  options.set(mp);
  mp.path_leash = transfer_path_leash(w.neutral, mp.reference_timing);
  return w;
}

SynthesisResult transfer_with(const PreparedSynthesis& p, const TransferRequest& request, TransferPlan w,
                              MixScratch& scratch) {
  MixParams& mp = w.params;
  // Strengths per part: each style's layer its strength per component, from the part that decides it.
  for (size_t style = 0; style < mp.layers.additive.size() && !w.given.empty(); ++style) {
    std::vector<std::pair<BodyPart, double>> given;
    for (const auto& [part, s] : w.given) given.emplace_back(part, s[style]);
    AdditiveLayer& layer = mp.layers.additive[style];
    layer.component_weights = weights_for_parts(given, p.decomposition->component_joints, layer.weight);
  }
  Json r;
  r["command"] = "transfer";
  r["content"] = request.content.file;
  // null: the content is its own neutral (the change is from the content to each style).
  r["neutral"] = w.neutral == TransferNeutral::kTake ? Json(request.neutral.file) : Json(nullptr);
  std::vector<std::string> style_files;
  for (const TakeSource& s : request.styles) style_files.push_back(s.file);
  r["styles"] = style_files;
  r["strengths"] = w.strengths;
  r["weights"] = take_weights(mp.layers, static_cast<int>(w.takes.size()));
  if (!mp.keys.empty()) r["keys"] = keys_json(mp.keys);
  if (!w.given.empty()) r["part_strengths"] = parts_json(w.given);
  return synthesize(p, request.options, mp, scratch, r);
}

}  // namespace

SynthesisResult transfer_style(const TransferRequest& request) {
  TransferPlan w = transfer_plan(request);
  MixScratch scratch;
  const PreparedSynthesis p = prepare(w.takes, request.options, request.options.decompose_params());
  return transfer_with(p, request, std::move(w), scratch);
}

PreparedSynthesis prepare_transfer(const TransferRequest& request) {
  const TransferPlan w = transfer_plan(request);
  return prepare(w.takes, request.options, request.options.decompose_params());
}

SynthesisResult transfer_prepared(const PreparedSynthesis& prepared, const TransferRequest& request,
                                  MixScratch& scratch) {
  TransferPlan w = transfer_plan(request);
  check_prepared_for(prepared, w.takes.size(), request.options, request.options.decompose_params());
  return transfer_with(prepared, request, std::move(w), scratch);
}

std::string result_positions_csv(const SynthesisResult& result) {
  std::vector<int> columns(result.joints.size());
  for (size_t i = 0; i < columns.size(); ++i) columns[i] = static_cast<int>(i);
  return positions_csv(result.mix.motion.world, columns, result.joints);
}

void write_synthesis_outputs(const SynthesisResult& result, const SynthesisOptions& options) {
  if (!options.out.empty()) write_motion_file(result.clip.clip, options.out);
  if (!options.positions_out.empty()) write_output(options.positions_out, result_positions_csv(result));
  if (!options.report.empty()) write_output(options.report, result.report.dump(2) + "\n");
}

}  // namespace mostyle::cli
