#include "engine/synthesize/mix_layers.h"

#include <cmath>
#include <string>

#include "engine/base/error.h"

namespace mostyle {
namespace {

bool in_takes(int take, int takes) { return take >= 0 && take < takes; }

// A layer's weight at component c: its own there, else its weight for the whole body.
double weight_at(const std::vector<double>& component_weights, double weight, Eigen::Index c) {
  return component_weights.empty() ? weight : component_weights[static_cast<size_t>(c)];
}

}  // namespace

bool MixLayers::per_component() const {
  for (const MixLayer& l : layers)
    if (!l.component_weights.empty()) return true;
  for (const AdditiveLayer& l : additive)
    if (!l.component_weights.empty()) return true;
  return false;
}

MixLayers take_layers(const std::vector<double>& weights, const Eigen::MatrixXd& component_weights) {
  MixLayers out;
  for (size_t i = 0; i < weights.size(); ++i) {
    MixLayer layer{static_cast<int>(i), weights[i], {}};
    if (component_weights.size() > 0 && static_cast<Eigen::Index>(i) < component_weights.cols()) {
      const auto column = component_weights.col(static_cast<Eigen::Index>(i));
      layer.component_weights.assign(column.data(), column.data() + column.size());
    }
    out.layers.push_back(std::move(layer));
  }
  return out;
}

MixLayers transfer_layers(const std::vector<double>& strengths, TransferNeutral neutral) {
  if (strengths.empty()) throw InputError("a transfer needs at least one style (--style)");
  MixLayers out;
  out.layers.push_back(MixLayer{0, 1.0, {}});
  const int from = neutral == TransferNeutral::kTake ? 1 : 0;
  for (size_t i = 0; i < strengths.size(); ++i) {
    const double s = strengths[i];
    if (!std::isfinite(s) || s < kMinStrength || s > kMaxStrength)
      throw InputError("expected a strength from -1 to 2, found " + std::to_string(s));
    out.additive.push_back(AdditiveLayer{from + 1 + static_cast<int>(i), from, s, {}});
  }
  return out;
}

std::vector<double> transfer_weights(const std::vector<double>& strengths, TransferNeutral neutral) {
  const MixLayers layers = transfer_layers(strengths, neutral);
  return take_weights(layers, static_cast<int>(strengths.size()) + (neutral == TransferNeutral::kTake ? 2 : 1));
}

// The layers in order, each additive layer's strength taken from its `from` as it is added to
// its take: a transfer's neutral is 0 - s_1 - s_2 ..., summed as the strengths come.
void take_weights(const MixLayers& layers, int takes, std::vector<double>& out) {
  out.assign(static_cast<size_t>(takes), 0.0);
  for (const MixLayer& l : layers.layers)
    if (in_takes(l.take, takes)) out[static_cast<size_t>(l.take)] += l.weight;
  for (const AdditiveLayer& l : layers.additive) {
    if (!in_takes(l.take, takes) || !in_takes(l.from, takes)) continue;
    out[static_cast<size_t>(l.take)] += l.weight;
    out[static_cast<size_t>(l.from)] -= l.weight;
  }
}

std::vector<double> take_weights(const MixLayers& layers, int takes) {
  std::vector<double> out;
  take_weights(layers, takes, out);
  return out;
}

void take_component_weights(const MixLayers& layers, int takes, int components, Eigen::MatrixXd& out) {
  if (!layers.per_component()) {
    out.resize(0, 0);
    return;
  }
  out.setZero(components, takes);
  for (Eigen::Index c = 0; c < components; ++c) {
    for (const MixLayer& l : layers.layers)
      if (in_takes(l.take, takes)) out(c, l.take) += weight_at(l.component_weights, l.weight, c);
    for (const AdditiveLayer& l : layers.additive) {
      if (!in_takes(l.take, takes) || !in_takes(l.from, takes)) continue;
      const double s = weight_at(l.component_weights, l.weight, c);
      out(c, l.take) += s;
      out(c, l.from) -= s;
    }
  }
}

}  // namespace mostyle
