#include "ui/model/document.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <system_error>

#include "ui/model/document_fields.h"

namespace mostyle::ui {
namespace {

std::string normal_absolute(const std::string& path) {
  std::error_code ec;
  const std::filesystem::path p = std::filesystem::absolute(path, ec);
  return (ec ? std::filesystem::path(path) : p).lexically_normal().string();
}

}  // namespace

bool in_range(double v, const Range& r) {
  if (!std::isfinite(v)) return false;
  if (v >= r.lo && v <= r.hi && !(r.open_low && v == r.lo)) return true;
  // A float slider's value: judged as the float it was (see the header).
  if (std::fabs(v) > 1e30) return false;
  const float f = static_cast<float>(v), lo = static_cast<float>(r.lo), hi = static_cast<float>(r.hi);
  return f >= lo && f <= hi && !(r.open_low && f <= lo);
}

bool differs_at(const Document& x, const Document& y, Stale what) {
  bool differs = false;
  document_fields(x, y, [&](const Field& field, const auto& a, const auto& b) {
    differs = differs || (field.stale == what && !same_value(a, b));
  });
  return differs;
}

Stale stale_after(const Document& before, const Document& after) {
  Stale stale = Stale::kNothing;
  document_fields(before, after, [&](const Field& field, const auto& x, const auto& y) {
    if (!same_value(x, y)) stale = std::max(stale, field.stale);
  });
  return stale;
}

// Equality from the one list of fields (ui/model/document_fields.h); a part compares as two documents
// that differ only there.
bool operator==(const Document& x, const Document& y) { return stale_after(x, y) == Stale::kNothing; }

bool operator==(const DecompositionControls& x, const DecompositionControls& y) {
  Document a, b;
  a.parameters = x;
  b.parameters = y;
  return a == b;
}

bool operator==(const DocumentControls& x, const DocumentControls& y) {
  Document a, b;
  a.controls = x;
  b.controls = y;
  return a == b;
}

bool operator==(const TakeLayer& x, const TakeLayer& y) {
  return x.weight == y.weight && x.component_weights == y.component_weights;
}

DocumentControls document_controls(DocumentControls controls) {
  const DocumentControls defaults;
  controls.selected_component = defaults.selected_component;
  controls.dtw_coordinate = defaults.dtw_coordinate;
  return controls;
}

bool same_files(const std::vector<std::string>& x, const std::vector<std::string>& y) {
  if (x.size() != y.size()) return false;
  for (size_t i = 0; i < x.size(); ++i)
    if (x[i] != y[i] && normal_absolute(x[i]) != normal_absolute(y[i])) return false;
  return true;
}

std::vector<double> layer_weights(const Document& d) {
  std::vector<double> out;
  for (const TakeLayer& layer : d.layers) out.push_back(layer.weight);
  return out;
}

void set_layer_weights(Document& d, const std::vector<double>& weights) {
  d.layers.resize(weights.size());
  for (size_t i = 0; i < weights.size(); ++i) d.layers[i].weight = weights[i];
}

double pair_alpha(const Document& d) { return d.layers.size() > 1 ? d.layers[1].weight : 0.5; }

namespace {

// ShownMotion k of the result is take order[k] of `d`, for a permutation or for a selection of takes;
// layers not one per take of d's are left as they are.
Document select_takes(const Document& d, const std::vector<int>& order, size_t takes) {
  Document selected = d;
  if (d.layers.size() == takes) {
    selected.layers.clear();
    for (int k : order) selected.layers.push_back(d.layers[static_cast<size_t>(k)]);
  }
  for (size_t k = 0; k < order.size(); ++k)
    if (order[k] == d.controls.neutral) selected.controls.neutral = static_cast<int>(k);
  return selected;
}

}  // namespace

Document reorder_takes(const Document& d, const std::vector<int>& order) {
  return select_takes(d, order, order.size());
}

Document keep_takes(const Document& d, const std::vector<int>& kept) {
  Document out = select_takes(d, kept, d.files.size());
  out.files.clear();
  for (int k : kept) out.files.push_back(d.files[static_cast<size_t>(k)]);
  const DocumentControls& c = d.controls;
  if (c.transfer && std::find(kept.begin(), kept.end(), c.neutral) == kept.end()) out.controls.content_neutral = true;
  if (out.layers.size() == kept.size() && !kept.empty() && !c.transfer) {  // a mix's weights sum to 1 again
    double sum = 0.0;
    for (const TakeLayer& layer : out.layers) sum += layer.weight;
    for (TakeLayer& layer : out.layers) layer.weight = sum != 0.0 ? layer.weight / sum : 1.0 / static_cast<double>(kept.size());
  }
  return out;
}

}  // namespace mostyle::ui
