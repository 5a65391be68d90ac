#pragma once
// Live styling: a style put on a motion-capture stream frame by frame as it
// arrives (Axis Neuron "BVH broadcasting": each frame a row of a known skeleton's channel
// values), using only that frame and the ones before it. The offline counterpart is a transfer
// on the content's timeline (`mostyle-cli transfer CONTENT --neutral N --style S --timing
// content`): content + strength x (style - neutral), the style and the neutral registered onto
// the content's cycles. The live styler adds the change averaged over the neutral's cycles at
// the phase the strikes so far predict, and keeps the stream's path; the transfer pairs one
// neutral cycle and one style cycle with each content cycle, warped onto it, and walks the mixed
// path. So the live result stays near the transfer's, not on it: it keeps the stream's planted
// feet and path, which no change by phase alone can do while matching the transfer's poses.
// Test: "live: a 20 s 120 fps CMU walk styled live follows the offline transfer" and the two after
// it (tests/engine/live/live_style_test.cpp), whose kOfflineMean holds the distance.
//
// Made once (heavy): the takes prepared with the neutral as the reference and each style's
// change by gait phase on the stream's bones (style_change.h). Then per frame:
//   1. the stream frame's major joints (FK), in its canonical frame (hips-relative, heading
//      removed; an up axis other than Y, read from the first frame, is turned to Y first);
//   2. its feet (live_feet.h) and gait phase (live_phase.h): the phase within the neutral's
//      cycle from the stream's own strikes so far; in a cycle the change at that phase, out of
//      one (standing, starting, turning on the spot) the posture change, eased between;
//   3. strength x change added to the canonical pose, placed back with the stream's own root and
//      heading, the stream's bone lengths kept; a planted foot (its ankle or its toe in contact,
//      heel strike to toe-off) held where the change put it when it landed (the ankle's change
//      over the neutral's stance, the foot moved whole), easing to the next stance's over the
//      swing (expected as long as the stream's last), the knee bent to reach (two-bone IK), the
//      toe on the foot's length from the ankle; no foot joint nearer its floor than the
//      stream's, up to twice the planted band (a style's low swing does not skim the floor
//      where the stream lifts the foot); no joint's change moving faster between two frames
//      than a fifth of the stream's fastest joint step lately, so no joint moves faster than
//      1.2 times the stream's fastest;
//   4. the stream skeleton's rotations solved from those positions (export_solve.h
//      ExportFrameSolver: the stream's own rotations where no target says otherwise, its twist
//      kept) and written as its channels.
// Strength 0 (once eased there) copies the frame through unchanged.
#include <memory>
#include <vector>

#include "engine/base/clip.h"

namespace mostyle {

// A transfer's layers (synthesize/mix_layers.h) with the stream as the content: each style an
// additive layer from the neutral at its strength, in the additive layers' range [kMinStrength,
// kMaxStrength].
struct LiveStyleSpec {
  std::vector<std::shared_ptr<const Clip>> takes;  // [neutral, style_1, ..., style_n] (n >= 1), as loaded
  std::vector<double> strengths;                    // one per style
};

// Strengths ease to new values over this time (set_strengths).
constexpr double kLiveStrengthEaseSeconds = 0.5;

class LiveStyle {
 public:
  // skeleton: the stream's (hierarchy and channels; any BVH rig with the major joints); fps: the
  // stream's frame rate. Heavy: prepares and registers the takes (prepare_takes at fps) and
  // makes the change tables. Throws InputError in one sentence on bad takes (no gait cycles in
  // the neutral, a style that cannot be registered onto them, missing major joints, naming the
  // file), a stream skeleton without hips and legs, a strength count that is not one per style,
  // a strength outside [-1, 2], or an fps outside (0, 1000].
  LiveStyle(const Skeleton& skeleton, double fps, const LiveStyleSpec& spec);
  ~LiveStyle();
  LiveStyle(const LiveStyle&) = delete;
  LiveStyle& operator=(const LiveStyle&) = delete;

  // Live controls: one strength per style, each in [-1, 2]; may change on any frame. The styled
  // frames ease to them over kLiveStrengthEaseSeconds (smoothstep), from where they are. Throws
  // InputError (nothing changed) on a wrong count or a value out of range.
  void set_strengths(const std::vector<double>& strengths);

  // Styles the next frame of the stream: `in` and `out` hold skeleton.channel_count values
  // (degrees, file units, the skeleton's channel order); they may not overlap. Uses only this
  // and earlier frames. A frame with a value that is not a finite number is not styled: `out`
  // repeats the frame before's output (`in` itself on the first frame) and the styler's state
  // stays as it was. Tens of microseconds a frame (bench: BM_LiveStyleFrame_Axis59,
  // tests/bench/live_style_bench.cpp); allocation-free; memory bounded however long it runs.
  void style_frame(const double* in, double* out);

  // The next frame is a new stream's first, as after construction: the feet, the gait phase, the
  // up axis, the foot holds and the speed limit's memory start afresh (a source reconnected may
  // stream another place, another performer), the strengths at their targets (no ease left).
  // The takes' change tables are kept: O(joints), nothing prepared again.
  void restart();

  // What the last frame styled showed (the editor's metrics, tests).
  double phase() const;            // [0, 1): within the neutral's gait cycle, as used
  bool in_cycle() const;           // the stream walks in cycles (else the posture change)
  double cycle_weight() const;     // [0, 1]: eased between posture (0) and the cycle's change (1)
  bool planted(int side) const;    // 0 left, 1 right: the foot is in contact
  const std::vector<double>& strengths() const;  // as eased on the last frame
  long frames() const;             // frames styled so far
  double body_height() const;      // the stream skeleton's standing height, file units
  // The stream's joint index of each major joint it is styled by (canonical order).
  const std::vector<int>& major_joints() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace mostyle
