#pragma once
// One timeline for several takes (the style palette): each take is aligned onto the
// reference (take 0) by its own time warp (time_warp.h); the common timeline's samples give,
// for every take, the (fractional) frame that matches the reference there.
#include <Eigen/Core>
#include <vector>

#include "engine/align/time_warp.h"

namespace mostyle {

// U samples; frames[i] holds take i's frame at each (take 0 is the reference). Every column is
// non-decreasing and, where a warp's slope is finite, no take advances more than one of its
// frames from one sample to the next. Take i matches the reference over samples first[i] to
// last[i]; outside them it holds its first or last matched frame.
struct CommonTimeline {
  std::vector<Eigen::VectorXd> frames;  // N vectors of U frames (working rate)
  std::vector<int> first, last;         // N: the samples where each take is matched
  int samples() const { return frames.empty() ? 0 : static_cast<int>(frames[0].size()); }
  int takes() const { return static_cast<int>(frames.size()); }
};

// The common timeline of warps[i - 1] (reference onto take i, warp.a the reference's frames).
// Every whole reference frame within the timeline is one of its samples: a mix played on the
// reference's own clock (a transfer on its content's timeline) reads the reference's poses, paths
// and contacts at its own frames, not interpolated between samples either side (which would
// smooth a swinging toe, so that strength 0 would not be the content).
// Tests: "one warp's common timeline has the reference's whole frames among its samples"
// (common_timeline_test.cpp); "palette: transfer identities" (tests/engine/synthesize/mix_palette_test.cpp).
// One warp or several, one way: the reference's frames that any warp matches (the union of their
// matched ranges, each range's ends among the samples), each stretch between knots (those ends and the whole frames) split evenly
// into steps of at most one reference frame and less where a matched take runs faster (1 / its
// largest slope over the stretch), but never below kMinCommonStep, so a warp that skips frames
// (the paper's) does not multiply the samples. Each take's frame is its warp read at the
// reference's frame, linearly between samples, held at its ends outside its range. A mix then
// plays the stretch every take with a weight matches, so a take with weight 0 does not shorten
// it. Where a warp holds the reference at a whole frame while its take plays on (a part of the
// take the reference lacks: a rest, an action of a take the reference's stillness is matched
// with), the timeline holds there too, a sample for each frame of that take, the other takes
// still: a mix gives it the time its weights give that take, none on the reference's clock. Throws InputError on no warps or an empty warp. O(sum of warp lengths + U x N).
constexpr double kMinCommonStep = 0.25;
CommonTimeline common_timeline(const std::vector<const TimeWarp*>& warps);

}  // namespace mostyle
