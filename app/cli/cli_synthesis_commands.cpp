#include "app/cli/cli_synthesis_commands.h"

#include <functional>
#include <iostream>
#include <memory>

#include "app/cli/cli_common.h"
#include "app/cli/cli_pipeline_common.h"
#include "app/cli/synthesis_request.h"

namespace mostyle::cli {
namespace {

// How a command names its takes and its timing choices in --help.
struct Words {
  std::string timing_help;
  std::string out_help;
};

// The options blend, mix and transfer share, bound to the request's fields (their defaults the
// request's).
void add_synthesis_options(CLI::App* cmd, SynthesisOptions& o, const Words& words) {
  add_align_options(cmd, o.align);
  cmd->add_option("--components,-k", o.components, "Number of components k")->capture_default_str();
  cmd->add_option("--sparsity,-f", o.sparsity, "Fraction of non-zeros kept in C, in (0, 1]")->capture_default_str();
  cmd->add_option("--iterations", o.iterations, "Decomposition iteration cap")->capture_default_str();
  cmd->add_flag("--no-limb-constraint", o.no_limb_constraint, "Skip the limb-length constraint (paper 3.7)");
  cmd->add_flag("--no-foot-lock", o.no_foot_lock, "Leave planted feet free (no foot-contact IK clean-up)");
  cmd->add_option("--timing", o.timing, words.timing_help)
      ->check(CLI::IsMember(std::vector<std::string>{o.timing_words.mixed, o.timing_words.reference}))
      ->capture_default_str();
  cmd->add_flag("--no-local", o.no_local,
                "Shared components may take channels anywhere instead of one connected piece of the skeleton each");
  cmd->add_flag("--components-only", o.components_only,
                "Shared mode: mix only what the k components reconstruct (the paper's synthesis), leaving out "
                "each take's residual detail");
  cmd->add_flag("--loop", o.loop, "Cut a seamless loop of 1 to 4 whole gait cycles (root travel per cycle kept)");
  cmd->add_option("--out", o.out, words.out_help)->check(written_motion_format());
  add_channels_option(cmd, o.channels);
  cmd->add_option("--positions-out", o.positions_out,
                  "CSV frame,joint,x,y,z of the result's final major-joint positions (after the foot lock)");
  cmd->add_option("--report", o.report, "JSON report");
}

// The request's warnings and notes on stderr, as every command prints them.
void print_messages(SynthesisOptions& o) {
  o.message = [](const std::string& line) { std::cerr << "mostyle: " << line << "\n"; };
}

// Writes the outputs; without --report, a few lines for the person on stdout.
int finish(const SynthesisResult& result, const SynthesisOptions& o) {
  write_synthesis_outputs(result, o);
  if (o.report.empty()) std::cout << report_summary(result.report, o.out, o.positions_out);
  return 0;
}

void add_blend_options(CLI::App* cmd, BlendRequest& args) {
  cmd->add_option("A", args.a.file, "Take A (the reference: its skeleton, units and world frame)")->required();
  cmd->add_option("B", args.b.file, "Take B (retargeted onto A and aligned onto it in time)")->required();
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
  add_synthesis_options(cmd, args.options,
                        {"blend: the output's timing moves from A's (alpha 0) to B's (alpha 1); a: keep A's timeline",
                         "File of the blend on A's skeleton: BVH (A's rotation orders), FBX when it ends in .fbx, glTF 2.0 in .glb or .gltf"});
}

}  // namespace

void add_blend_command(CLI::App& app, std::function<int()>* run) {
  auto* cmd = app.add_subcommand("blend", "Blend the styles of two takes");
  auto args = std::make_shared<BlendRequest>();
  add_blend_options(cmd, *args);
  cmd->callback([=] {
    *run = [=] {
      print_messages(args->options);
      return finish(blend_takes(*args), args->options);
    };
  });
}

void add_mix_command(CLI::App& app, std::function<int()>* run) {
  auto* cmd = app.add_subcommand("mix", "Mix the styles of 2 to 16 takes with weights (the style palette)");
  struct Args {
    std::vector<std::string> files;
    MixRequest request;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("TAKES", args->files,
                  "BVH takes; the first is the reference (its skeleton, units, world frame and start)")
      ->required();
  cmd->add_option("--weights", args->request.weights,
                  "One weight per take, comma separated, decimals or fractions (1/3), summing to 1 (within 0.001, "
                  "then divided by their sum), each from -0.5 to 1.5 (default: equal)");
  cmd->add_option("--part-weights", args->request.part_weights,
                  "PART:w1,w2,...: one body part's weights, one per take (legs, arms, spine, left-leg, right-leg, "
                  "left-arm, right-arm; repeat for several, a side wins over both sides); the rest take --weights");
  cmd->add_option("--weights-at", args->request.weights_at,
                  "Weights keyed in time, T:w1,w2,...;T:... (T in seconds of the output, one weight per take, "
                  "summing to 1; eased between keys, held before the first and after the last); replaces --weights");
  add_synthesis_options(cmd, args->request.options,
                        {"mix: the output's timing is mixed with the weights; reference: keep the first take's timeline",
                         "File of the result on the first take's skeleton: BVH, FBX when it ends in .fbx, glTF 2.0 in .glb or .gltf"});
  cmd->callback([=] {
    *run = [=] {
      for (const std::string& f : args->files) args->request.takes.push_back({f, nullptr});
      print_messages(args->request.options);
      return finish(mix_takes(args->request), args->request.options);
    };
  });
}

namespace {

// What `transfer` is given.
struct TransferArgs {
  std::vector<std::string> styles;
  TransferRequest request;
};

void add_transfer_options(CLI::App* cmd, TransferArgs& args) {
  TransferRequest& r = args.request;
  cmd->add_option("CONTENT", r.content.file,
                  "BVH take that keeps its skeleton, path, length and timing base and takes on the style")
      ->required();
  cmd->add_option("--neutral", r.neutral.file,
                  "BVH take of the action without the style; without it CONTENT is its own neutral (CONTENT + s "
                  "(STYLE - CONTENT))");
  cmd->add_option("--style", args.styles, "BVH take of the action in the style (repeat for several styles)")
      ->required();
  cmd->add_option("--strength", r.strengths,
                  "How much of each style, one per --style (comma separated or repeated, decimals or fractions), "
                  "from -1 to 2; 0 leaves CONTENT as it is, 1 adds the whole change (without --neutral, 1 is the "
                  "style on CONTENT's timeline; default 1)");
  cmd->add_option("--part-strength", r.part_strengths,
                  "PART:s1,...: one body part's strengths, one per style (legs, arms, spine, left-leg, right-leg, "
                  "left-arm, right-arm); the rest take --strength");
  cmd->add_option("--strength-at", r.strength_at,
                  "Strength keyed in time, T:s,T:s,... (T in seconds of the output; with several styles "
                  "T:s1,s2;T:...; eased between keys, held before the first and after the last); replaces --strength");
  // The content keeps its timing and length by default: a transfer styles one's own take, which
  // has to stay in sync with whatever it was made for; the style's timing is there on request.
  add_synthesis_options(cmd, r.options,
                        {"content: keep CONTENT's timeline and length; mix: the output's timing is mixed with the "
                         "weights too (the style's timing change, so the length changes)",
                         "File of the result on CONTENT's skeleton: BVH, FBX when it ends in .fbx, glTF 2.0 in .glb or .gltf"});
}

}  // namespace

void add_transfer_command(CLI::App& app, std::function<int()>* run) {
  auto* cmd = app.add_subcommand(
      "transfer",
      "Put the style change from a neutral take (or, without one, from the content itself) to a styled one onto a "
      "take of your own");
  auto args = std::make_shared<TransferArgs>();
  add_transfer_options(cmd, *args);
  cmd->callback([=] {
    *run = [=] {
      for (const std::string& f : args->styles) args->request.styles.push_back({f, nullptr});
      print_messages(args->request.options);
      return finish(transfer_style(args->request), args->request.options);
    };
  });
}

}  // namespace mostyle::cli
