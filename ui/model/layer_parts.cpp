#include "ui/model/layer_parts.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace mostyle::ui {
namespace {

// The layers' component weights sized for the decomposition's k components, on its regions.
void size_for(Document& d, const Decomposed& decomposition) {
  const size_t k = static_cast<size_t>(decomposition.components());
  for (TakeLayer& layer : d.layers) layer.component_weights.resize(k);
  d.controls.component_regions.clear();
  for (const ComponentJoints& joints : decomposition.component_joints) d.controls.component_regions.push_back(joints.region);
}

bool covers(const Decomposed& decomposition, BodyPart part, int c) {
  return part_covers(part, decomposition.component_joints[static_cast<size_t>(c)].region);
}

}  // namespace

std::vector<double> component_row(const Document& d, int c, const std::vector<double>& weights) {
  std::vector<double> row = weights;
  for (size_t i = 0; i < d.layers.size() && i < row.size(); ++i) {
    const std::vector<std::optional<double>>& own = d.layers[i].component_weights;
    if (c >= 0 && static_cast<size_t>(c) < own.size() && own[static_cast<size_t>(c)]) row[i] = *own[static_cast<size_t>(c)];
  }
  return row;
}

bool component_set(const Document& d, int c) {
  for (const TakeLayer& layer : d.layers)
    if (c >= 0 && static_cast<size_t>(c) < layer.component_weights.size() && layer.component_weights[static_cast<size_t>(c)])
      return true;
  return false;
}

void set_component_row(Document& d, const Decomposed& decomposition, int c, const std::optional<std::vector<double>>& row) {
  if (c < 0 || c >= decomposition.components()) return;
  size_for(d, decomposition);
  for (size_t i = 0; i < d.layers.size(); ++i)
    d.layers[i].component_weights[static_cast<size_t>(c)] =
        row && i < row->size() ? std::optional<double>((*row)[i]) : std::nullopt;
}

int first_component_of(const Decomposed& decomposition, BodyPart part) {
  for (int c = 0; c < decomposition.components(); ++c)
    if (covers(decomposition, part, c)) return c;
  return -1;
}

void set_part_row(Document& d, const Decomposed& decomposition, BodyPart part, const std::optional<std::vector<double>>& row) {
  for (int c = 0; c < decomposition.components(); ++c)
    if (covers(decomposition, part, c)) set_component_row(d, decomposition, c, row);
}

int part_from_take(const Document& d, const Decomposed& decomposition, BodyPart part) {
  int from = -1;
  for (int c = 0; c < decomposition.components(); ++c) {
    if (!covers(decomposition, part, c)) continue;
    if (!component_set(d, c)) return -1;
    const std::vector<double> row = component_row(d, c, std::vector<double>(d.layers.size(), 0.0));
    int one = -1;
    for (size_t i = 0; i < row.size(); ++i) {
      if (row[i] == 1.0 && one < 0) one = static_cast<int>(i);
      else if (row[i] != 0.0) return -1;
    }
    if (one < 0 || (from >= 0 && one != from)) return -1;
    from = one;
  }
  return from;
}

std::vector<double> set_weight_keeping_sum(std::vector<double> w, int i, double value, double lo, double hi) {
  const int n = static_cast<int>(w.size());
  if (i < 0 || i >= n) return w;
  value = std::clamp(value, lo, hi);
  if (n == 1) {
    w[0] = 1.0;
    return w;
  }
  double others = 0.0;
  for (int j = 0; j < n; ++j)
    if (j != i) others += w[static_cast<size_t>(j)];
  const double rest = 1.0 - value;
  for (int j = 0; j < n; ++j) {
    if (j == i) continue;
    double& x = w[static_cast<size_t>(j)];
    x = std::abs(others) > 1e-9 ? x * rest / others : rest / (n - 1);
  }
  w[static_cast<size_t>(i)] = value;
  // Scaling may push another take out of range: clamp it and give the difference to take i.
  double sum = 0.0;
  for (int j = 0; j < n; ++j)
    if (j != i) {
      double& x = w[static_cast<size_t>(j)];
      x = std::clamp(x, lo, hi);
      sum += x;
    }
  w[static_cast<size_t>(i)] = 1.0 - sum;
  return w;
}

}  // namespace mostyle::ui
