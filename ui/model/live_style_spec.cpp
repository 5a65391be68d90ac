#include "ui/model/live_style_spec.h"

#include <algorithm>

#include "engine/base/error.h"
#include "engine/synthesize/mix_layers.h"
#include "ui/model/keyed_weights.h"

namespace mostyle::ui {

LiveStylePlan live_style_plan(const Document& document, int takes) {
  LiveStylePlan plan;
  if (takes < 2) return plan;
  // The stream stands in for the first take (a transfer's content); the neutral is the first
  // take itself, or a transfer's neutral take; every other take is a style added at its layer's
  // weight (a mix's weight, a transfer's strength), as the mix's additive layers have it.
  const int neutral = document.controls.transfer ? transfer_neutral(document.controls, takes) : 0;
  const std::vector<double> weights = constant_weights(document, takes);
  plan.takes.push_back(neutral);
  for (int i = 1; i < takes; ++i) {
    if (i == neutral) continue;
    plan.takes.push_back(i);
    plan.strengths.push_back(std::clamp(weights[static_cast<size_t>(i)], kMinStrength, kMaxStrength));
  }
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
