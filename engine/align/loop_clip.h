#pragma once
// Loop clips: takes made to be played on repeat (a game character's walk or run: one cycle of
// 0.5 to 2 s whose last pose joins its first). Only the pose is compared (joint positions in the
// canonical frame: the root's travel and heading taken out), so a loop whose root moves on (root
// motion) is one as well as one that stays in place.
#include <Eigen/Core>

namespace mostyle {

// A loop clip's frames per repeat, L: frame f + L shows frame f's pose. local: F x 3M canonical
// poses (canonical_frame.h), any units. A step is the RMS over joints of the distance between
// neighbouring frames' poses; the seam is measured two ways:
//   last repeats first (L = F - 1): the last pose against the first;
//   first follows last (L = F): the first pose against the last moved on by one step (the mean of
//   the first and the last frame's steps);
// the smaller seam gives L. The clip is a loop when that seam is at most the median step (it
// plays on without a hitch larger than its own steps), its first and last steps are not near
// still (a take from rest to rest stops at its ends), it is at most max_frames long, and its
// pose does not come back to its first pose more than max_returns times in between (a take of
// many cycles that happens to end near its start pose is not a loop: each cycle is a return).
// Returns 0 for a take that is not a loop, still, or shorter than 4 frames. O(F x M).
int loop_clip_frames(const Eigen::MatrixXd& local, int max_frames, int max_returns);

}  // namespace mostyle
