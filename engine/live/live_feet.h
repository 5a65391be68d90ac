#pragma once
// Foot contacts of a stream, frame by frame, with no future frames (the live styler's,
// live_style.h): when each foot is planted, and where a foot strikes, as soon as the frames so
// far tell it. The offline detection (measure/foot_contact.h detect_foot_contacts) reads each frame
// with the frames either side of it; this one reads frame t - 1 once frame t has come (its
// speed a central difference), against the floor of the frames before it, and keeps what it
// decided: a contact starts once its ankle has been low and slow for min_contact_seconds and
// ends once it has been high or fast for longer than max_gap_seconds, its thresholds a little
// wider to end than to start (hysteresis), so a foot near a threshold does not flicker.
// Thresholds are relative to the leg's length: any unit; Y up (the styler turns other up axes
// to Y first); any frame rate from 24 to 120 fps and beyond.
#include <Eigen/Core>
#include <array>
#include <vector>

#include "engine/measure/foot_contact.h"

namespace mostyle {

// A contact's thresholds to end it, as multiples of those to start it (FootContactOptions).
constexpr double kLiveContactHysteresis = 1.5;
// The floor under a foot is the low percentile (foot_contact.h's) of its ankle's heights over
// this many seconds before the frame.
constexpr double kLiveFloorSeconds = 1.5;

// One foot's state after a frame.
struct LiveFoot {
  bool planted = false;    // in contact (as of frame `decided`)
  long strike = -1;        // the frame its last contact started (a foot strike); -1: none yet
  long lift = -1;          // the frame its last contact ended; -1: none yet
  bool struck_now = false; // this frame's update found a new contact (its first frame `strike`)
  bool lifted_now = false; // this frame's update ended a contact (its first frame off `lift`)
};

class LiveFeet {
 public:
  // leg_length: thigh + shin (file units, > 0); fps > 0; options: the offline detection's
  // thresholds (height_fraction, speed_fraction, min_contact_seconds, max_gap_seconds).
  // Allocates its windows (kLiveFloorSeconds of heights per foot).
  LiveFeet(double leg_length, double fps, const FootContactOptions& options = {});

  // The next frame: both ankles' positions (Y up, file units). Decides frame `decided()` (one
  // frame back) and updates feet(). O(floor window), allocation-free.
  void update(const Eigen::Vector3d& left_ankle, const Eigen::Vector3d& right_ankle);

  const LiveFoot& foot(int side) const { return feet_[static_cast<size_t>(side)]; }
  long frames() const { return frames_; }       // frames given so far
  long decided() const { return frames_ - 2; }  // the last frame decided (-1 before two frames)
  // The floor under a foot (its ankle's height when planted), as of the last frame decided.
  double floor(int side) const { return floors_[static_cast<size_t>(side)]; }

 private:
  double leg_ = 1.0, fps_ = 30.0;
  FootContactOptions options_;
  int min_frames_ = 1, gap_frames_ = 0;
  long frames_ = 0;
  std::array<LiveFoot, 2> feet_;
  std::array<std::array<Eigen::Vector3d, 3>, 2> recent_;  // the last three ankle positions, newest last
  std::array<std::vector<double>, 2> heights_;             // ring of heights over the floor window
  std::vector<double> scratch_;                            // the window, partly sorted
  std::array<double, 2> floors_{{0.0, 0.0}};
  std::array<int, 2> run_{{0, 0}};  // frames in a row meeting the other state's condition
};

}  // namespace mostyle
