#pragma once
// blend, mix and transfer as functions: a request (the takes and every option, with the
// command's defaults) in, the result and its report out. mostyle-cli's commands fill a request
// from their flags and the Python module from its keyword arguments, so both run one code path
// and write the same files. No CLI11 here: the module includes it.
#include <Eigen/Core>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "engine/align/prepare_takes.h"
#include "engine/base/clip.h"
#include "engine/decompose/decompose_takes.h"
#include "engine/export/export_solve.h"
#include "engine/synthesize/mix_palette.h"

namespace mostyle::cli {

using Json = nlohmann::ordered_json;

// A take a request reads: a file, or a clip already in memory.
struct TakeSource {
  std::string file;                  // path or FILE#ANIMATION; what the report names the take by
  std::shared_ptr<const Clip> clip;  // when set, taken as it is and `file` is not read
};

// The two values of --timing: the one that mixes the takes' timing and the one that keeps the
// reference's timeline.
struct TimingWords {
  const char* mixed;
  const char* reference;
};
inline constexpr TimingWords kBlendTiming{"blend", "a"};
inline constexpr TimingWords kMixTiming{"mix", "reference"};
inline constexpr TimingWords kTransferTiming{"mix", "content"};

// --fps, --time-base, --dtw, --align-on, --max-slope, --closed-ends, --band.
struct AlignOptions {
  double fps = 30.0;
  int band = -1;
  std::string time_base = "cycles";
  std::string dtw = "slope";
  std::string align_on = "auto";
  int max_slope = 2;
  bool closed_ends = false;
  PrepareOptions options() const;  // validated; throws InputError
};

// A line for the person running the request: "warning: ..." (an alignment's or a reader's
// warning) or "note: ..." (which animation of several a reader took).
using MessageSink = std::function<void(const std::string& line)>;

// The options blend, mix and transfer share: alignment, decomposition, clean-up, outputs.
struct SynthesisOptions {
  explicit SynthesisOptions(TimingWords words) : timing_words(words), timing(words.mixed) {}

  AlignOptions align;
  int components = 10;
  double sparsity = 0.1;
  int iterations = 100;
  bool no_limb_constraint = false, no_foot_lock = false, loop = false, components_only = false, no_local = false;
  TimingWords timing_words;
  std::string timing;         // timing_words.mixed or .reference
  std::string channels;       // layout of `out`: "", "as-source" or "rotations" (channel_layout.h)
  std::string out, positions_out, report;  // files to write; "" writes none
  // Solve the result's clip on the reference's skeleton even when `out` is empty (the Python
  // module hands its rotations over).
  bool solve_clip = false;
  MessageSink message;        // none: warnings and notes are dropped

  DecomposeParams decompose_params() const;
  void set(MixParams& mp) const;  // timing, residual and clean-up
  void Validate() const;          // --timing and --channels; throws InputError
};

// What `blend` is given.
struct BlendRequest {
  TakeSource a, b;
  std::string mapping_a, mapping_b;  // major-joint mapping files ("" none)
  double alpha = 0.5;
  std::string mode = "shared";
  int basic = 0;
  std::vector<double> basic_sparsities;
  int swap = 0;
  std::vector<double> component_alpha;
  std::vector<std::string> part_alpha;  // "PART:a" or "PART:a,PART:a", as --part-alpha takes them
  std::string alpha_at;                 // "T:a,T:a,..."
  SynthesisOptions options{kBlendTiming};
};

// What `mix` is given.
struct MixRequest {
  std::vector<TakeSource> takes;
  std::string weights;                    // "w1,w2,..." (decimals or fractions); "": equal
  std::vector<std::string> part_weights;  // "PART:w1,w2,..."
  std::string weights_at;                 // "T:w1,w2,...;T:..."
  SynthesisOptions options{kMixTiming};
};

// What `transfer` is given.
struct TransferRequest {
  TransferRequest() {
    options.align.fps = 0.0;  // the content keeps its own frame rate unless asked otherwise
    options.timing = kTransferTiming.reference;
  }
  TakeSource content;
  TakeSource neutral;  // none when both its file and its clip are empty: the content is its own
  std::vector<TakeSource> styles;
  std::vector<std::string> strengths;       // one per style, each "s" or "s1,s2"; none: 1 each
  std::vector<std::string> part_strengths;  // "PART:s1,..."
  std::string strength_at;                  // "T:s,T:s,..." or "T:s1,s2;T:..."
  SynthesisOptions options{kTransferTiming};
};

struct SynthesisResult {
  std::shared_ptr<const PreparedTakes> prepared;
  std::shared_ptr<const Decomposed> decomposition;
  MixResult mix;                          // mix.motion.world: F x 3M, the reference's units and world
  std::vector<std::string> joints;        // the M major joints' names (the reference's)
  bool solved = false;                    // `clip` holds the result (out or solve_clip asked for it)
  ExportResult clip;                      // on the reference's skeleton, in the layout asked for
  Json report;                            // what --report writes
};

// A request's takes read, prepared and decomposed: what a mix with other weights starts from, so
// that a weight change runs only the mix and the result's solve.
struct PreparedSynthesis {
  std::vector<TakeSource> takes;  // as mixed: the first the reference (a transfer's content, neutral, styles)
  std::shared_ptr<const PreparedTakes> prepared;
  std::shared_ptr<const Decomposed> decomposition;
  AlignOptions align;             // what they were prepared with
  DecomposeParams decompose;
  StageTimes times;               // load, preprocess, dtw and decompose, as they took
};

// Each checks its numbers before reading a file, reads the takes (the first the reference),
// prepares, decomposes and mixes them, solves the clip when asked, and fills the report. Writes
// nothing: write_synthesis_outputs does. Throws InputError on bad input, with the CLI's sentence.
SynthesisResult blend_takes(const BlendRequest& request);
SynthesisResult mix_takes(const MixRequest& request);
SynthesisResult transfer_style(const TransferRequest& request);

// mix_takes and transfer_style in two steps: prepare_* checks the request's numbers and reads,
// prepares and decomposes its takes (the slow part); *_prepared mixes the request's weights (or
// strengths) on them and gives what mix_takes or transfer_style gives for that request, the
// report's timings the preparation's. A request handed to *_prepared names the same takes (not
// read again: the prepared ones are mixed) with the same alignment and decomposition options;
// its weights, keys, parts, timing, clean-up and outputs are its own. scratch is kept from one
// call to the next, so that a re-mix allocates nothing in the mix (mix_palette.h). Throw
// InputError as mix_takes and transfer_style do, and when the request's takes or alignment and
// decomposition options are not the prepared ones. *_prepared: O(the mix + the solve).
PreparedSynthesis prepare_mix(const MixRequest& request);
SynthesisResult mix_prepared(const PreparedSynthesis& prepared, const MixRequest& request, MixScratch& scratch);
PreparedSynthesis prepare_transfer(const TransferRequest& request);
SynthesisResult transfer_prepared(const PreparedSynthesis& prepared, const TransferRequest& request,
                                  MixScratch& scratch);

// Writes options.out, options.positions_out and options.report, those given. Throws InputError
// when one cannot be written.
void write_synthesis_outputs(const SynthesisResult& result, const SynthesisOptions& options);

// The CSV --positions-out writes: frame,joint,x,y,z of the result's major joints.
std::string result_positions_csv(const SynthesisResult& result);

}  // namespace mostyle::cli
