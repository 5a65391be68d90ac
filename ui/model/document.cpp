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

bool operator==(const BlendParameters& x, const BlendParameters& y) {
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

bool operator==(const PaletteControls& x, const PaletteControls& y) {
  Document a, b;
  a.controls.palette = x;
  b.controls.palette = y;
  return a == b;
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

double pair_alpha(const Document& d) { return d.weights.size() == 2 ? d.weights[1] : 0.5; }

namespace {

// Take k of the result is take order[k] of `d`, for a permutation or for a selection of takes;
// per-take vectors of another length than d's takes are left as they are.
Document select_takes(const Document& d, const std::vector<int>& order, size_t takes) {
  const size_t n = order.size();
  auto selected = [&](const std::vector<double>& v) {
    if (v.size() != takes) return v;
    std::vector<double> out(n);
    for (size_t k = 0; k < n; ++k) out[k] = v[static_cast<size_t>(order[k])];
    return out;
  };
  const PaletteControls& c = d.controls.palette;
  Document selected_document = d;
  selected_document.weights = selected(d.weights);
  PaletteControls& out = selected_document.controls.palette;
  out.strengths = selected(c.strengths);
  for (std::vector<double>& row : out.part_weights) row = selected(row);
  for (size_t k = 0; k < n; ++k) {
    if (order[k] == c.neutral) out.neutral = static_cast<int>(k);
    if (order[k] == c.content) out.content = static_cast<int>(k);
  }
  return selected_document;
}

}  // namespace

Document reorder_takes(const Document& d, const std::vector<int>& order) {
  return select_takes(d, order, order.size());
}

Document keep_takes(const Document& d, const std::vector<int>& kept) {
  Document out = select_takes(d, kept, d.files.size());
  out.files.clear();
  for (int k : kept) out.files.push_back(d.files[static_cast<size_t>(k)]);
  const PaletteControls& c = d.controls.palette;
  if (c.transfer && std::find(kept.begin(), kept.end(), c.neutral) == kept.end()) out.controls.palette.content_neutral = true;
  out.controls.palette.content = 0;  // the content is the reference, whichever take that now is
  if (out.weights.size() == kept.size() && !kept.empty()) {
    double sum = 0.0;
    for (double w : out.weights) sum += w;
    for (double& w : out.weights) w = sum != 0.0 ? w / sum : 1.0 / static_cast<double>(kept.size());
  }
  return out;
}

}  // namespace mostyle::ui
