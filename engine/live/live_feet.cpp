#include "engine/live/live_feet.h"

#include <algorithm>
#include <cmath>

namespace mostyle {
namespace {

// The floor's percentile of the ankle's heights, as the offline detection takes it.
constexpr double kLiveFloorPercentile = 0.05;
constexpr double kTimeEpsilon = 1e-9;

}  // namespace

LiveFeet::LiveFeet(double leg_length, double fps, const FootContactOptions& options)
    : leg_(leg_length), fps_(fps), options_(options) {
  // As the offline detection counts them: a contact at least min_contact_seconds to the nearest
  // frame (one at least), a break of at most max_gap_seconds filled.
  min_frames_ = std::max(1, static_cast<int>(std::lround(options_.min_contact_seconds * fps_)));
  gap_frames_ = static_cast<int>(std::floor(options_.max_gap_seconds * fps_ + kTimeEpsilon));
  const size_t window = static_cast<size_t>(std::max(2L, std::lround(kLiveFloorSeconds * fps_)));
  for (auto& h : heights_) h.assign(window, 0.0);
  scratch_.assign(window, 0.0);
}

void LiveFeet::update(const Eigen::Vector3d& left_ankle, const Eigen::Vector3d& right_ankle) {
  const Eigen::Vector3d ankles[2] = {left_ankle, right_ankle};
  const size_t window = heights_[0].size();
  const long t = frames_++;
  for (int side = 0; side < 2; ++side) {
    auto& recent = recent_[static_cast<size_t>(side)];
    recent[0] = recent[1];
    recent[1] = recent[2];
    recent[2] = ankles[side];
    std::vector<double>& heights = heights_[static_cast<size_t>(side)];
    heights[static_cast<size_t>(t) % window] = ankles[side].y();
    LiveFoot& foot = feet_[static_cast<size_t>(side)];
    foot.struck_now = foot.lifted_now = false;
    const long at = t - 1;  // the frame decided: its speed needs this frame
    if (at < 0) continue;
    // The floor: the low percentile of the heights so far within the window (up to frame t).
    const size_t count = static_cast<size_t>(std::min<long>(t + 1, static_cast<long>(window)));
    std::copy(heights.begin(), heights.begin() + static_cast<std::ptrdiff_t>(count), scratch_.begin());
    const size_t k = static_cast<size_t>(kLiveFloorPercentile * static_cast<double>(count - 1));
    std::nth_element(scratch_.begin(), scratch_.begin() + static_cast<std::ptrdiff_t>(k),
                     scratch_.begin() + static_cast<std::ptrdiff_t>(count));
    floors_[static_cast<size_t>(side)] = scratch_[k];
    // Frame t - 1's height over the floor and its speed (central difference; one-sided at the
    // first frame), leg lengths and leg lengths per second.
    const double height = (recent[1].y() - scratch_[k]) / leg_;
    const double speed = at == 0 ? (recent[2] - recent[1]).norm() * fps_ / leg_
                                 : (recent[2] - recent[0]).norm() * fps_ / (2.0 * leg_);
    int& run = run_[static_cast<size_t>(side)];
    if (!foot.planted) {
      // Low and slow for min_frames in a row: a contact from the first of them.
      const bool starts = height <= options_.height_fraction && speed <= options_.speed_fraction;
      run = starts ? run + 1 : 0;
      if (run >= min_frames_) {
        foot.planted = true;
        foot.strike = at - (run - 1);
        foot.struck_now = true;
        run = 0;
      }
    } else {
      // High or fast (beyond the wider thresholds) for longer than the gap: it ended at the first.
      const bool ends = height > kLiveContactHysteresis * options_.height_fraction ||
                        speed > kLiveContactHysteresis * options_.speed_fraction;
      run = ends ? run + 1 : 0;
      if (run > gap_frames_) {
        foot.planted = false;
        foot.lift = at - (run - 1);
        foot.lifted_now = true;
        run = 0;
      }
    }
  }
}

}  // namespace mostyle
