#pragma once
// TEMPORARY stand-in: copies each frame unchanged. The real styler (branch live-style) replaces
// this file and live_style.cpp at its merge; the API below is the agreed one.
#include <memory>
#include <vector>

#include "engine/io/clip.h"

namespace mostyle {

struct LiveStyleSpec {
  std::vector<std::shared_ptr<const Clip>> takes;  // [neutral, style_1, ..., style_n] (n >= 1), as loaded
  std::vector<double> strengths;                    // one per style
};

class LiveStyle {
 public:
  // skeleton: the stream's (the --skeleton file's hierarchy and channels); fps: the stream's frame rate.
  // Heavy (prepares and registers the takes). Throws InputError in one sentence on bad takes.
  LiveStyle(const Skeleton& skeleton, double fps, const LiveStyleSpec& spec);
  ~LiveStyle();
  void set_strengths(const std::vector<double>& strengths);  // live controls
  // Styles the next frame of the stream: `in` and `out` hold skeleton.channel_count values
  // (degrees, file units, the skeleton's channel order). Uses only this and earlier frames.
  void style_frame(const double* in, double* out);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace mostyle
