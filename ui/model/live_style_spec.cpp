#include "ui/model/live_style_spec.h"

#include <algorithm>

#include "engine/base/error.h"

namespace mostyle::ui {

std::vector<double> live_strengths(const Document& document, int takes) {
  std::vector<double> strengths;
  if (takes == 2) {
    strengths.push_back(pair_alpha(document));
  } else {
    const std::vector<double>& set = document.controls.palette.strengths;
    for (int i = 1; i < takes; ++i) strengths.push_back(static_cast<size_t>(i) < set.size() ? set[static_cast<size_t>(i)] : 1.0);
  }
  for (double& s : strengths) s = std::clamp(s, -1.0, 2.0);
  return strengths;
}

LiveStyleSpec live_style_spec(const PreparedTakes& takes, const Document& document) {
  if (takes.size() < 2)
    throw InputError("Live: load two takes or more first: the first is the neutral, the others the styles.");
  LiveStyleSpec spec;
  for (const PreparedTake& take : takes.takes) spec.takes.push_back(take.clip);
  spec.strengths = live_strengths(document, takes.size());
  return spec;
}

}  // namespace mostyle::ui
