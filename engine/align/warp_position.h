#pragma once
// Where on a take's own alignment warp (alignment.h Alignment::warp, the pair's DTW view and its
// per-sample match quality) a sample of the common timeline lies. The common timeline has its
// own samples (every whole reference frame among them, common_timeline.h), so a mix's output
// frame (MixResult::sample) is not an index into the warp: it is found on the warp by where the
// two takes are.
#include <Eigen/Core>

#include "engine/align/common_timeline.h"
#include "engine/align/time_warp.h"

namespace mostyle {

// The fractional sample of `warp` (the reference onto take `take` >= 1, one of the warps the
// timeline was made of) at the timeline's fractional `sample`: where the warp's a + b reaches the
// reference's frame plus the take's there (a + b grows along a warp; both are read linearly).
// Clamped to the warp's samples; 0 for an empty warp or timeline. O(log U).
double warp_position(const TimeWarp& warp, const CommonTimeline& timeline, int take, double sample);

}  // namespace mostyle
