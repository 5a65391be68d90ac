#pragma once
// What a mix's result is judged by, against its takes: the limb lengths, the planted feet and the
// fastest joint (no pops), and each take's own fit and feet. One report of them, which the CLI's
// summary and --report and the editor's Metrics panel all read, so that each says the same.
#include <optional>
#include <vector>

#include "engine/align/prepare_takes.h"
#include "engine/decompose/decompose_takes.h"
#include "engine/synthesize/mix_palette.h"

namespace mostyle {

struct TakeMeasures {
  std::optional<double> fit_error;  // what the components do not rebuild (RMSE), reference units; none before the decomposition
  double planted_speed = 0.0;       // its planted feet on its own frames (PreparedTake::planted), reference units per second
  double fastest_joint = 0.0;       // its fastest joint (PreparedTake::fastest_joint), reference units per second
};

// A result's measures (MixResult::motion after the clean-up), each beside what the takes give.
struct ResultMeasures {
  double limb_length_max_error = 0.0;  // the largest bone-length error, reference units
  double planted_raw = 0.0;            // its planted feet before the foot lock, units per second
  double planted_cleaned = 0.0;        // after it (the raw speed when the lock is off)
  double planted_inputs = 0.0;         // the takes' own, weighted as mixed (MixResult::foot_sliding_inputs)
  double fastest_joint = 0.0;          // its fastest joint, units per second
  double fastest_inputs = 0.0;         // the fastest of the takes mixed (MixResult::fastest_inputs)
  // cleaned over inputs, and fastest over the takes': none where the takes' is 0 (still feet, a
  // still pose).
  std::optional<double> planted_ratio() const;
  std::optional<double> fastest_ratio() const;
};

struct MixMeasures {
  // The body's height (FootRig::body_height) that planted feet are measured with and that speeds
  // are told as a share of; reference units.
  double body_height = 0.0;
  std::vector<TakeMeasures> takes;       // one per prepared take
  std::optional<ResultMeasures> result;  // none without a result, or for a preview not finished
};

// The measures of `mix` (none: the takes' alone) mixed from `prepared`, decomposed as
// `decomposition` (none: no fit errors yet). A preview mix (MixParams::preview) not finished
// has no result measures. O(takes): the result's were measured by its clean-up.
MixMeasures mix_measures(const PreparedTakes& prepared, const Decomposed* decomposition, const MixResult* mix,
                         bool finished = true);

}  // namespace mostyle
