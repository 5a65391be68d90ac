#include "ui/model/live_style_spec.h"

#include <algorithm>

#include "engine/base/error.h"
#include "ui/model/keyed_weights.h"

namespace mostyle::ui {

LiveStylePlan live_style_plan(const Document& document, int takes) {
  LiveStylePlan plan;
  if (takes < 2) return plan;
  const PaletteControls& palette = document.controls.palette;
  if (takes == 2) {
    plan.takes = {0, 1};
    plan.strengths = {pair_alpha(document)};
  } else if (!palette.transfer) {
    // The stream is the first take's performer: the mix's weights of the others are how much of
    // each is put on it (the first take's own weight is what is left of the stream).
    const std::vector<double> weights = constant_weights(document, takes);
    for (int i = 0; i < takes; ++i) plan.takes.push_back(i);
    plan.strengths.assign(weights.begin() + 1, weights.end());
  } else {
    const int neutral = transfer_neutral(palette, takes);  // 0: the content is its own neutral
    plan.takes.push_back(neutral);
    for (int i = 1; i < takes; ++i) {
      if (i == neutral) continue;
      plan.takes.push_back(i);
      const size_t at = static_cast<size_t>(i);
      plan.strengths.push_back(at < palette.strengths.size() ? palette.strengths[at] : 1.0);
    }
  }
  for (double& s : plan.strengths) s = std::clamp(s, -1.0, 2.0);
  return plan;
}

std::vector<double> live_strengths(const Document& document, int takes) {
  return live_style_plan(document, takes).strengths;
}

LiveStyleSpec live_style_spec(const PreparedTakes& takes, const Document& document) {
  if (takes.size() < 2)
    throw InputError("Live: load two takes or more first: a neutral and the styles.");
  const LiveStylePlan plan = live_style_plan(document, takes.size());
  LiveStyleSpec spec;
  for (int i : plan.takes) spec.takes.push_back(takes.takes[static_cast<size_t>(i)].clip);
  spec.strengths = plan.strengths;
  return spec;
}

}  // namespace mostyle::ui
