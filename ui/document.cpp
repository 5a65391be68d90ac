#include "ui/document.h"

#include <filesystem>
#include <system_error>

namespace mostyle::ui {
namespace {

std::string normal_absolute(const std::string& path) {
  std::error_code ec;
  const std::filesystem::path p = std::filesystem::absolute(path, ec);
  return (ec ? std::filesystem::path(path) : p).lexically_normal().string();
}

}  // namespace

bool operator==(const BlendParameters& x, const BlendParameters& y) {
  return x.alpha == y.alpha && x.components == y.components && x.sparsity == y.sparsity;
}

bool operator==(const PaletteControls& x, const PaletteControls& y) {
  return x.weights == y.weights && x.per_part == y.per_part && x.part_weights == y.part_weights &&
         x.transfer == y.transfer && x.content == y.content && x.neutral == y.neutral && x.strengths == y.strengths &&
         x.ghosts == y.ghosts;
}

bool operator==(const SessionControls& x, const SessionControls& y) {
  return x.mode == y.mode && x.per_component == y.per_component && x.component_alpha == y.component_alpha &&
         x.basic_motions == y.basic_motions && x.basic_sparsities == y.basic_sparsities &&
         x.swap_level == y.swap_level && x.foot_lock == y.foot_lock && x.align == y.align &&
         x.timing_a == y.timing_a && x.loop == y.loop && x.residual == y.residual &&
         x.selected_component == y.selected_component && x.dtw_coordinate == y.dtw_coordinate &&
         x.palette == y.palette;
}

bool operator==(const Document& x, const Document& y) {
  return x.parameters == y.parameters && x.controls == y.controls && x.files == y.files && x.overlay == y.overlay;
}

SessionControls document_controls(SessionControls controls) {
  const SessionControls defaults;
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

PaletteControls reorder_takes(const PaletteControls& c, const std::vector<int>& order) {
  const size_t n = order.size();
  auto reordered = [&](const std::vector<double>& v) {
    if (v.size() != n) return v;
    std::vector<double> out(n);
    for (size_t k = 0; k < n; ++k) out[k] = v[static_cast<size_t>(order[k])];
    return out;
  };
  PaletteControls out = c;
  out.weights = reordered(c.weights);
  out.strengths = reordered(c.strengths);
  for (std::vector<double>& row : out.part_weights) row = reordered(row);
  for (size_t k = 0; k < n; ++k) {
    if (order[k] == c.neutral) out.neutral = static_cast<int>(k);
    if (order[k] == c.content) out.content = static_cast<int>(k);
  }
  return out;
}

bool decomposition_differs(const Document& x, const Document& y) {
  return x.parameters.components != y.parameters.components || x.parameters.sparsity != y.parameters.sparsity ||
         x.controls.mode != y.controls.mode || x.controls.basic_motions != y.controls.basic_motions ||
         x.controls.basic_sparsities != y.controls.basic_sparsities;
}

}  // namespace mostyle::ui
