// TEMPORARY stand-in (see live_style.h): the pass-through styler.
#include "engine/live/live_style.h"

#include <algorithm>
#include <string>

#include "engine/io/error.h"

namespace mostyle {

struct LiveStyle::State {
  int channels = 0;
  std::vector<double> strengths;
};

LiveStyle::LiveStyle(const Skeleton& skeleton, double /*fps*/, const LiveStyleSpec& spec)
    : state_(std::make_unique<State>()) {
  if (spec.takes.size() < 2)
    throw InputError("live styling takes a neutral take and at least one style, found " +
                     std::to_string(spec.takes.size()) + " takes");
  if (spec.strengths.size() + 1 != spec.takes.size())
    throw InputError("expected " + std::to_string(spec.takes.size() - 1) + " strengths, one per style, found " +
                     std::to_string(spec.strengths.size()));
  state_->channels = skeleton.channel_count;
  state_->strengths = spec.strengths;
}

LiveStyle::~LiveStyle() = default;

void LiveStyle::set_strengths(const std::vector<double>& strengths) { state_->strengths = strengths; }

void LiveStyle::style_frame(const double* in, double* out) { std::copy(in, in + state_->channels, out); }

}  // namespace mostyle
