#include "app/cli/cli_synthesis_commands.h"

#include <chrono>
#include <cmath>
#include <functional>
#include <iostream>
#include <memory>

#include "app/cli/cli_common.h"
#include "app/cli/cli_pipeline_common.h"
#include "engine/align/warp_position.h"
#include "engine/export/export_frames.h"
#include "engine/export/export_solve.h"
#include "engine/base/clock.h"
#include "engine/base/error.h"
#include "engine/kinematics/units.h"
#include "engine/decompose/decompose_takes.h"
#include "engine/synthesize/mix_palette.h"
#include "engine/run/blend_params.h"

namespace mostyle::cli {
namespace {

using Clock = std::chrono::steady_clock;
// How a command names its takes and its timing choices in --help.
struct Words {
  std::string mixed_timing;      // --timing's value that mixes the takes' timing ("blend", "mix")
  std::string reference_timing;  // the value that keeps the reference's timeline ("a", "reference", "content")
  std::string timing_help;
  std::string out_help;
  std::string default_timing;    // --timing's default; empty: mixed_timing
};

// The options blend, mix and transfer share: alignment, decomposition, clean-up, outputs.
struct SynthesisFlags {
  AlignFlags align;
  int components = 10;
  double sparsity = 0.1;
  int iterations = 100;
  bool no_limb = false, no_foot_lock = false, loop = false, components_only = false, no_local = false;
  std::string timing, mixed_timing;
  std::string out, positions_out, report;
  ChannelsFlag channels;

  void add_to(CLI::App* cmd, const Words& words) {
    mixed_timing = words.mixed_timing;
    timing = words.default_timing.empty() ? words.mixed_timing : words.default_timing;
    align.add_to(cmd);
    cmd->add_option("--components,-k", components, "Number of components k")->capture_default_str();
    cmd->add_option("--sparsity,-f", sparsity, "Fraction of non-zeros kept in C, in (0, 1]")->capture_default_str();
    cmd->add_option("--iterations", iterations, "Decomposition iteration cap")->capture_default_str();
    cmd->add_flag("--no-limb-constraint", no_limb, "Skip the limb-length constraint (paper 3.7)");
    cmd->add_flag("--no-foot-lock", no_foot_lock, "Leave planted feet free (no foot-contact IK clean-up)");
    cmd->add_option("--timing", timing, words.timing_help)
        ->check(CLI::IsMember(std::vector<std::string>{words.mixed_timing, words.reference_timing}))
        ->capture_default_str();
    cmd->add_flag("--no-local", no_local,
                  "Shared components may take channels anywhere instead of one connected piece of the skeleton each");
    cmd->add_flag("--components-only", components_only,
                  "Shared mode: mix only what the k components reconstruct (the paper's synthesis), leaving out "
                  "each take's residual detail");
    cmd->add_flag("--loop", loop, "Cut a seamless loop of 1 to 4 whole gait cycles (root travel per cycle kept)");
    cmd->add_option("--out", out, words.out_help)->check(written_motion_format());
    channels.add_to(cmd);
    cmd->add_option("--positions-out", positions_out,
                    "CSV frame,joint,x,y,z of the result's final major-joint positions (after the foot lock)");
    cmd->add_option("--report", report, "JSON report");
  }

  DecomposeParams decompose_params() const {
    DecomposeParams dp;
    dp.components = components;
    dp.sparsity = sparsity;
    dp.max_iterations = iterations;
    dp.local = !no_local;
    return dp;
  }

  void set(MixParams& mp) const {
    mp.reference_timing = timing != mixed_timing;
    mp.residual = !components_only;
    mp.finish.limb_lengths = !no_limb;
    mp.finish.foot_lock = !no_foot_lock;
    mp.finish.loop = loop;
  }
};

struct Prepared {
  std::shared_ptr<const PreparedTakes> prepared;
  std::shared_ptr<const Decomposed> decomposition;
  StageTimes times;
};

// Reads the takes (the first the reference), prepares and decomposes them; the alignment's
// warnings go to stderr. Mapping files name the reference's joints and the second take's.
Prepared prepare(const std::vector<std::string>& files, const SynthesisFlags& flags, const DecomposeParams& dp,
                 const std::string& mapping_a = "", const std::string& mapping_b = "") {
  Prepared p;
  PrepareOptions o = flags.align.options();
  const auto t0 = Clock::now();
  std::vector<std::shared_ptr<const Clip>> clips;
  for (const std::string& f : files) clips.push_back(std::make_shared<const Clip>(load_clip(f)));
  p.times.load_ms = ms_since(t0);
  o.mapping_a = load_mapping(mapping_a);
  o.mapping_b = load_mapping(mapping_b);
  p.prepared = prepare_takes(clips, o, nullptr, &p.times);
  for (const PreparedTake& t : p.prepared->takes)
    for (const std::string& w : t.alignment.warnings) std::cerr << "mostyle: warning: " << w << "\n";
  p.decomposition = decompose_takes(*p.prepared, dp, nullptr, &p.times);
  return p;
}

// Mixes, writes the outputs and the report. `r` already holds the command's own fields;
// `words` adds the fields only it reports, once the mix is made.
int run_synthesis(const Prepared& p, const std::vector<std::string>& files, const SynthesisFlags& flags,
                  const MixParams& mp, Json r, const std::function<void(const MixResult&, Json&)>& words = {}) {
  const PreparedTakes& palette = *p.prepared;
  const Decomposed& d = *p.decomposition;
  StageTimes times = p.times;
  MixScratch scratch;
  MixResult result;
  mix_palette(palette, d, mp, scratch, result, &times);
  const Eigen::MatrixXd& world = result.motion.world;
  ExportFit fit;
  const Clip& reference = *palette.takes.front().clip;
  const ChannelLayout layout = flags.channels.layout(reference);
  if (!flags.out.empty()) {
    const auto t_export = Clock::now();
    fit = export_blend_bvh(reference, export_joints(palette), world, source_frames_in_clip(palette, result),
                           palette.fps, flags.out, layout)
              .fit;
    times.export_ms = ms_since(t_export);
  }
  const std::vector<std::string>& names = palette.takes.front().names;
  if (!flags.positions_out.empty()) {
    std::vector<int> columns(names.size());
    for (size_t i = 0; i < columns.size(); ++i) columns[i] = static_cast<int>(i);
    write_output(flags.positions_out, positions_csv(world, columns, names));
  }
  r["frames"] = world.rows();
  r["fps"] = palette.fps;
  // A loop lasts all its frames (the next repeat follows its last); a clip, first frame to last.
  r["duration_s"] = flags.loop ? world.rows() / palette.fps : motion_length_s(world.rows(), palette.fps);
  r["components"] = flags.components;
  r["sparsity"] = flags.sparsity;
  r["joints"] = names;
  r["timing"] = flags.timing;
  r["residual"] = mp.residual;
  Json takes = Json::array();
  for (int i = 0; i < palette.size(); ++i) {
    Json t;
    t["file"] = files[static_cast<size_t>(i)];
    t["weight"] = mp.weights[static_cast<size_t>(i)];
    t["major_joints"] = major_joints_json(palette.takes[static_cast<size_t>(i)].mapping,
                                          palette.takes[static_cast<size_t>(i)].clip->skeleton);
    t["reconstruction_rmse"] = d.rmse[static_cast<size_t>(i)];
    t["foot_sliding"] = take_foot_sliding(palette, i);
    if (i > 0) t["alignment"] = alignment_json(palette, i);
    // Its own file's frames at the working rate (null where a take registered by cycles gives
    // its posture only), and which of its cycles each output frame shows (-1: none).
    t["source_frames"] = vector_json(frames_in_take(palette.takes[static_cast<size_t>(i)], result.sources.col(i)));
    const Eigen::VectorXi shown = cycles_shown(palette.takes[static_cast<size_t>(i)], result.sources.col(i));
    t["source_cycles"] = std::vector<int>(shown.data(), shown.data() + shown.size());
    const CycleRegistration& registration = palette.takes[static_cast<size_t>(i)].registration;
    const PreparedTake& take = palette.takes[static_cast<size_t>(i)];
    t["time_base"] = take.alignment.by_structure ? "structure"
                     : registration.empty()      ? "whole"
                     : registration.posture_only() ? "posture"
                                                   : "cycles";
    t["structure"] = action_structure_summary(take.cycles, palette.fps);
    takes.push_back(t);
  }
  r["takes"] = takes;
  r["common_timeline"] = {{"samples", palette.samples()},
                          {"reference_first", palette.timeline.frames[0][0]},
                          {"reference_last", palette.timeline.frames[0][palette.samples() - 1]}};
  if (flags.loop) r["loop"] = loop_json(result.motion.loop, palette.fps);
  r["iterations"] = d.iterations;
  r["local"] = d.params.local && d.shared() != nullptr;
  r["component_joints"] = component_joints_json(d.component_joints, names);
  r["component_regions"] = component_regions_json(d.component_joints);
  r["limb_length_max_error"] = result.motion.limb_length_max_error;
  if (!flags.out.empty()) {
    r["export_fit"] = {{"max", fit.max}, {"mean", fit.mean}};
    r["channels"] = channel_layout_name(layout);
  }
  r["foot_lock"] = mp.finish.foot_lock;
  r["foot_sliding"] = foot_sliding_json(result, palette.feet.body_height);
  r["skeleton_height"] = guess_units(*palette.takes.front().clip).height;
  r["timings_ms"] = {{"load", times.load_ms},         {"preprocess", times.preprocess_ms},
                     {"dtw", times.dtw_ms},           {"decompose", times.decompose_ms},
                     {"synthesize", times.synthesize_ms}, {"postprocess", times.postprocess_ms},
                     {"export", times.export_ms}};
  if (words) words(result, r);
  if (!flags.report.empty()) write_output(flags.report, r.dump(2) + "\n");
  else std::cout << report_summary(r, flags.out, flags.positions_out);
  return 0;
}

// A blend's alpha is B's weight and 1 - alpha is A's: refused outside the range mix allows a
// weight (kMinMixWeight to kMaxMixWeight, symmetric about 1/2, so A's weight is in it too).
void check_alpha(double alpha, const std::string& flag) {
  if (!(alpha >= kMinMixWeight && alpha <= kMaxMixWeight))
    throw InputError("expected " + flag + " from " + number(kMinMixWeight) + " to " + number(kMaxMixWeight) +
                     " (B's weight; A's is 1 - alpha), found " + number(alpha));
}

// What `blend` is given.
struct BlendArgs {
  std::string a, b, mapping_a, mapping_b;
  double alpha = 0.5;
  std::string mode = "shared";
  int basic = 0;
  std::vector<double> basic_sparsities;
  int swap = 0;
  std::vector<double> component_alpha;
  std::vector<std::string> part_alpha;
  std::string alpha_at;
  SynthesisFlags flags;
};

void add_blend_options(CLI::App* cmd, BlendArgs& args) {
  cmd->add_option("A", args.a, "Take A (the reference: its skeleton, units and world frame)")->required();
  cmd->add_option("B", args.b, "Take B (retargeted onto A and aligned onto it in time)")->required();
  cmd->add_option("--mapping-a", args.mapping_a, "Major-joint mapping file for A (see assets/mappings)");
  cmd->add_option("--mapping-b", args.mapping_b, "Major-joint mapping file for B");
  cmd->add_option("--alpha", args.alpha, "0 gives A, 1 gives B; from -0.5 to 1.5")->capture_default_str();
  cmd->add_option("--mode", args.mode, "shared (one component set, alpha 1 is B) or paper (core components)")
      ->check(CLI::IsMember({"shared", "paper"}))
      ->capture_default_str();
  cmd->add_option("--basic", args.basic, "Paper mode: decompose into M basic motions")->capture_default_str();
  cmd->add_option("--basic-sparsity", args.basic_sparsities, "Sparsity of each basic motion")->delimiter(',');
  cmd->add_option("--swap", args.swap, "Basic motion (0-based) whose core is taken from B")->capture_default_str();
  cmd->add_option("--part-alpha", args.part_alpha,
                  "Shared mode: PART:a, the alpha of one body part's components (legs, arms, spine, left-leg, "
                  "right-leg, left-arm, right-arm; repeat for several, a side wins over both sides); the rest "
                  "take --alpha");
  cmd->add_option("--component-alpha", args.component_alpha, "Shared mode: one alpha per component, comma separated")
      ->delimiter(',');
  cmd->add_option("--alpha-at", args.alpha_at,
                  "Alpha keyed in time, T:a,T:a,... (T in seconds of the output; eased between keys, held before "
                  "the first and after the last); replaces --alpha (shared mode)");
  args.flags.add_to(cmd, {"blend", "a", "blend: the output's timing moves from A's (alpha 0) to B's (alpha 1); a: keep A's timeline",
                          "File of the blend on A's skeleton: BVH (A's rotation orders), FBX when it ends in .fbx, glTF 2.0 in .glb or .gltf",
                          ""});
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
  report["reconstruction_rmse"] = {{"a", d.rmse[0]}, {"b", d.rmse[1]}};
  report["component_nonzero_fraction"] = {{"a", d.nonzero[0]}, {"b", d.nonzero[1]}};
  report["foot_sliding"]["a"] = take_foot_sliding(prepared, 0);
  report["foot_sliding"]["b"] = take_foot_sliding(prepared, 1);
}

int run_blend(const BlendArgs& args) {
  DecomposeParams dp = args.flags.decompose_params();
  dp.mode = args.mode == "paper" ? BlendMode::kPaper : BlendMode::kShared;
  dp.basic_motions = args.basic;
  dp.basic_sparsities = args.basic_sparsities;
  if (!args.part_alpha.empty()) {
    if (!args.component_alpha.empty()) throw InputError("give --part-alpha or --component-alpha, not both");
    if (dp.mode != BlendMode::kShared) throw InputError("--part-alpha needs shared mode (--mode shared)");
  }
  // Every alpha is checked before the files are read.
  check_alpha(args.alpha, "--alpha");
  for (double a : args.component_alpha) check_alpha(a, "--component-alpha");
  const std::vector<std::pair<BodyPart, double>> given = part_alphas(args.part_alpha);
  const auto keys = parse_keys(args.alpha_at, "--alpha-at", 1);
  for (const auto& key : keys) check_alpha(key.second[0], "--alpha-at");
  const std::vector<std::string> files{args.a, args.b};
  const Prepared p = prepare(files, args.flags, dp, args.mapping_a, args.mapping_b);
  const Decomposed& d = *p.decomposition;
  BlendParams bp;
  bp.alpha = args.alpha;
  bp.component_alpha = args.component_alpha;
  if (!given.empty()) bp.component_alpha = weights_for_parts(given, d.component_joints, args.alpha);
  bp.swap_level = args.swap;
  MixParams mp = blend_mix_params(bp, d);
  for (const auto& key : keys) mp.keys.push_back({key.first, {1.0 - key.second[0], key.second[0]}});
  args.flags.set(mp);
  Json r;
  r["command"] = "blend";
  r["a"] = args.a;
  r["b"] = args.b;
  r["alpha"] = args.alpha;
  if (!mp.keys.empty()) r["keys"] = keys_json(mp.keys);
  r["mode"] = args.mode;
  if (args.basic > 0) {
    r["basic_motions"] = args.basic;
    r["swap"] = args.swap;
  }
  return run_synthesis(p, files, args.flags, mp, r, [&](const MixResult& result, Json& report) {
    add_pair_words(*p.prepared, d, result, report);
  });
}

}  // namespace

void add_blend_command(CLI::App& app, std::function<int()>* run) {
  auto* cmd = app.add_subcommand("blend", "Blend the styles of two takes");
  auto args = std::make_shared<BlendArgs>();
  add_blend_options(cmd, *args);
  cmd->callback([=] { *run = [=] { return run_blend(*args); }; });
}

void add_mix_command(CLI::App& app, std::function<int()>* run) {
  auto* cmd = app.add_subcommand("mix", "Mix the styles of 2 to 16 takes with weights (the style palette)");
  struct Args {
    std::vector<std::string> files;
    std::string weights;
    std::vector<std::string> part_weights;
    std::string weights_at;
    SynthesisFlags flags;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("TAKES", args->files,
                  "BVH takes; the first is the reference (its skeleton, units, world frame and start)")
      ->required();
  cmd->add_option("--weights", args->weights,
                  "One weight per take, comma separated, decimals or fractions (1/3), summing to 1 (within 0.001, "
                  "then divided by their sum), each from -0.5 to 1.5 (default: equal)");
  cmd->add_option("--part-weights", args->part_weights,
                  "PART:w1,w2,...: one body part's weights, one per take (legs, arms, spine, left-leg, right-leg, "
                  "left-arm, right-arm; repeat for several, a side wins over both sides); the rest take --weights");
  cmd->add_option("--weights-at", args->weights_at,
                  "Weights keyed in time, T:w1,w2,...;T:... (T in seconds of the output, one weight per take, "
                  "summing to 1; eased between keys, held before the first and after the last); replaces --weights");
  args->flags.add_to(cmd, {"mix", "reference", "mix: the output's timing is mixed with the weights; reference: keep the first take's timeline",
                          "File of the result on the first take's skeleton: BVH, FBX when it ends in .fbx, glTF 2.0 in .glb or .gltf",
                           ""});
  cmd->callback([=] {
    *run = [=] {
      const size_t n = args->files.size();
      if (n < 2 || n > static_cast<size_t>(kMaxPaletteTakes))
        throw InputError("mix takes from 2 to " + std::to_string(kMaxPaletteTakes) + " BVH files, found " +
                         std::to_string(n));
      MixParams mp;
      const std::vector<double> typed =
          args->weights.empty() ? std::vector<double>(n, 1.0 / double(n)) : parse_numbers(args->weights, "--weights");
      mp.weights = normalized_weights(typed);
      for (const auto& [seconds, w] : parse_keys(args->weights_at, "--weights-at", n))
        mp.keys.push_back({seconds, normalized_weights(w)});
      if (!mp.keys.empty() && !args->part_weights.empty())
        throw InputError("give --weights-at or --part-weights, not both: keys in time mix the whole body");
      auto given = parse_part_entries(args->part_weights, "--part-weights", n);
      for (auto& entry : given) entry.second = normalized_weights(entry.second);
      // Refuse bad weights before the files are read.
      mp.Validate(static_cast<int>(n), 0);
      for (const auto& [part, w] : given) {
        MixParams check = mp;
        check.weights = w;
        try {
          check.Validate(static_cast<int>(n), 0);
        } catch (const InputError& e) {
          throw InputError(std::string("--part-weights ") + body_part_name(part) + ": " + e.what());
        }
      }
      args->flags.set(mp);
      const Prepared p = prepare(args->files, args->flags, args->flags.decompose_params());
      if (!given.empty()) mp.component_weights = part_weights(given, p.decomposition->component_joints, mp.weights);
      Json r;
      r["command"] = "mix";
      r["weights"] = mp.weights;
      r["weights_typed"] = typed;
      if (!mp.keys.empty()) r["keys"] = keys_json(mp.keys);
      if (!given.empty()) {
        Json parts = Json::object();
        for (const auto& [part, w] : given) parts[body_part_name(part)] = w;
        r["part_weights"] = parts;
      }
      return run_synthesis(p, args->files, args->flags, mp, r);
    };
  });
}

namespace {

// What `transfer` is given.
struct TransferArgs {
  std::string content, neutral;
  std::vector<std::string> styles;
  std::vector<std::string> strengths;
  std::vector<std::string> part_strengths;
  std::string strength_at;
  SynthesisFlags flags;
};

void add_transfer_options(CLI::App* cmd, TransferArgs& args) {
  args.flags.align.fps = 0.0;  // the content keeps its own frame rate unless --fps says otherwise
  cmd->add_option("CONTENT", args.content,
                  "BVH take that keeps its skeleton, path, length and timing base and takes on the style")
      ->required();
  cmd->add_option("--neutral", args.neutral,
                  "BVH take of the action without the style; without it CONTENT is its own neutral (CONTENT + s "
                  "(STYLE - CONTENT))");
  cmd->add_option("--style", args.styles, "BVH take of the action in the style (repeat for several styles)")
      ->required();
  cmd->add_option("--strength", args.strengths,
                  "How much of each style, one per --style (comma separated or repeated, decimals or fractions), "
                  "from -1 to 2; 0 leaves CONTENT as it is, 1 adds the whole change (without --neutral, 1 is the "
                  "style on CONTENT's timeline; default 1)");
  cmd->add_option("--part-strength", args.part_strengths,
                  "PART:s1,...: one body part's strengths, one per style (legs, arms, spine, left-leg, right-leg, "
                  "left-arm, right-arm); the rest take --strength");
  cmd->add_option("--strength-at", args.strength_at,
                  "Strength keyed in time, T:s,T:s,... (T in seconds of the output; with several styles "
                  "T:s1,s2;T:...; eased between keys, held before the first and after the last); replaces --strength");
  // The content keeps its timing and length by default: a transfer styles one's own take, which
  // has to stay in sync with whatever it was made for; the style's timing is there on request.
  args.flags.add_to(cmd, {"mix", "content",
                          "content: keep CONTENT's timeline and length; mix: the output's timing is mixed with the "
                          "weights too (the style's timing change, so the length changes)",
                          "File of the result on CONTENT's skeleton: BVH, FBX when it ends in .fbx, glTF 2.0 in .glb or .gltf",
                          "content"});
}

// One strength per style (--strength, comma separated or repeated; default 1 each).
std::vector<double> transfer_strengths(const TransferArgs& args) {
  const size_t styles = args.styles.size();
  std::vector<double> strengths;
  for (const std::string& s : args.strengths)
    for (double v : parse_numbers(s, "--strength")) strengths.push_back(v);
  if (args.strengths.empty()) strengths.assign(styles, 1.0);
  if (strengths.size() != styles)
    throw InputError("expected " + std::to_string(styles) + " strengths, one per --style, found " +
                     std::to_string(strengths.size()));
  return strengths;
}

int run_transfer(const TransferArgs& args) {
  const size_t styles = args.styles.size();
  const std::vector<double> strengths = transfer_strengths(args);
  // The takes: the content, the neutral when given, the styles. Without a neutral the content
  // is its own: the same mix, on one take fewer, with the content's weight 1 - sum s.
  const TransferNeutral neutral = args.neutral.empty() ? TransferNeutral::kContent : TransferNeutral::kTake;
  std::vector<std::string> files{args.content};
  if (neutral == TransferNeutral::kTake) files.push_back(args.neutral);
  files.insert(files.end(), args.styles.begin(), args.styles.end());
  if (files.size() > static_cast<size_t>(kMaxPaletteTakes))
    throw InputError("transfer takes at most " + std::to_string(kMaxPaletteTakes - (files.size() - styles)) +
                     " styles");
  MixParams mp;
  mp.weights = transfer_weights(strengths, neutral);
  // Content 1, neutral minus the strengths' sum (or the content 1 minus it), each style its strength.
  mp.min_weight = transfer_min_weight(static_cast<int>(styles));
  mp.max_weight = transfer_max_weight(static_cast<int>(styles));
  mp.feet_of_reference = true;
  for (const auto& [seconds, s] : parse_keys(args.strength_at, "--strength-at", styles))
    mp.keys.push_back({seconds, transfer_weights(s, neutral)});
  if (!mp.keys.empty() && !args.part_strengths.empty())
    throw InputError("give --strength-at or --part-strength, not both: keys in time style the whole body");
  const auto given = parse_part_entries(args.part_strengths, "--part-strength", styles);
  std::vector<std::pair<BodyPart, std::vector<double>>> given_weights;
  for (const auto& [part, s] : given) given_weights.emplace_back(part, transfer_weights(s, neutral));
  args.flags.set(mp);
  mp.path_leash = transfer_path_leash(neutral, mp.reference_timing);
  const Prepared p = prepare(files, args.flags, args.flags.decompose_params());
  if (!given_weights.empty())
    mp.component_weights = part_weights(given_weights, p.decomposition->component_joints, mp.weights);
  Json r;
  r["command"] = "transfer";
  r["content"] = args.content;
  // null: the content is its own neutral (the change is from the content to each style).
  r["neutral"] = neutral == TransferNeutral::kTake ? Json(args.neutral) : Json(nullptr);
  r["styles"] = args.styles;
  r["strengths"] = strengths;
  r["weights"] = mp.weights;
  if (!mp.keys.empty()) r["keys"] = keys_json(mp.keys);
  if (!given.empty()) {
    Json parts = Json::object();
    for (const auto& [part, s] : given) parts[body_part_name(part)] = s;
    r["part_strengths"] = parts;
  }
  return run_synthesis(p, files, args.flags, mp, r);
}

}  // namespace

void add_transfer_command(CLI::App& app, std::function<int()>* run) {
  auto* cmd = app.add_subcommand(
      "transfer",
      "Put the style change from a neutral take (or, without one, from the content itself) to a styled one onto a "
      "take of your own");
  auto args = std::make_shared<TransferArgs>();
  add_transfer_options(cmd, *args);
  cmd->callback([=] { *run = [=] { return run_transfer(*args); }; });
}

}  // namespace mostyle::cli
