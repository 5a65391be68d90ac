#pragma once
// Where the editor's panels go, as a pure function of the display size (compute_layout): a left
// column (takes, parameters), a right column (components, metrics, files), and along the bottom
// the takes' layers (layers_panel.h) between the columns over the playback bar, which spans the window. The side
// columns take about a quarter of the width each (340 to 420 px), and the central 30% x 30% of
// the window stays clear for the skeletons at every size from 1280x720 to 2560x1440
// (tests/ui/panels/layout_test.cpp).
//
// Panels take their rectangle with ImGuiCond_Always when state.view.reset_layout is set (the
// display size changed, the first frame included, or Reset layout was asked for) and with
// ImGuiCond_FirstUseEver otherwise: a panel the animator moved stays where they put it until the
// window is resized or the layout reset.
#include <algorithm>
#include <array>
#include <cstddef>

#include <imgui.h>

#include "ui/model/editor_state.h"

namespace mostyle::ui {

constexpr float kLayoutMargin = 12.0f;      // panels to the window's edges, pixels
constexpr float kLayoutGap = 8.0f;          // between panels, pixels
constexpr float kSideFraction = 0.24f;      // a side column's share of the width...
constexpr float kSideMin = 340.0f;          // ...within these bounds, pixels
constexpr float kSideMax = 420.0f;
constexpr float kClearFraction = 0.30f;     // the centre left clear: this share of width and height
constexpr float kPlaybackBarHeight = 44.0f; // the playback bar with the editor's 16 px font

// A rectangle in display pixels, from the top-left corner, y down.
struct PanelRect {
  float x = 0.0f, y = 0.0f, w = 0.0f, h = 0.0f;
  float right() const { return x + w; }
  float bottom() const { return y + h; }
  bool overlaps(const PanelRect& o) const { return x < o.right() && o.x < right() && y < o.bottom() && o.y < bottom(); }
  bool inside(float width, float height) const {
    return x >= 0.0f && y >= 0.0f && right() <= width && bottom() <= height;
  }
};

// The panels the layout places, in compute_layout's order.
enum class PanelId { kTakes, kParameters, kFiles, kComponents, kMetrics, kLayers, kPlayback };
constexpr int kPanelCount = 7;

// The ImGui window title (and id) of each panel.
inline const char* panel_title(PanelId id) {
  static const char* const kTitles[kPanelCount] = {"Takes",      "Parameters", "Files",   "Components",
                                                   "Metrics",    "Layers",     "Playback"};
  return kTitles[static_cast<int>(id)];
}

// The central kClearFraction x kClearFraction of a width x height display.
inline PanelRect clear_centre(float width, float height) {
  const float half = 0.5f * kClearFraction;
  return PanelRect{(0.5f - half) * width, (0.5f - half) * height, kClearFraction * width, kClearFraction * height};
}

// Every panel's rectangle for a width x height display, indexed by PanelId; bar_height is the
// playback bar's (its font and padding). Inside the display and clear of clear_centre() for any
// display of at least 640x360; the panels do not overlap one another. Pure, O(1).
// takes: the rows the Takes panel lists (a pair's A, B and blend: 3; a palette's mix and takes),
// so that it is as tall as they need (within 18% to 50% of the left column).
inline std::array<PanelRect, kPanelCount> compute_layout(float width, float height,
                                                         float bar_height = kPlaybackBarHeight, int takes = 3) {
  const float m = kLayoutMargin, g = kLayoutGap;
  const PanelRect centre = clear_centre(width, height);
  // Side columns: a share of the width within bounds, but never into the centre (small windows).
  const float side =
      std::max(1.0f, std::min(std::clamp(kSideFraction * width, kSideMin, kSideMax), centre.x - m - g));
  std::array<PanelRect, kPanelCount> r{};
  auto at = [&r](PanelId id) -> PanelRect& { return r[static_cast<size_t>(id)]; };

  at(PanelId::kPlayback) = PanelRect{m, height - m - bar_height, std::max(1.0f, width - 2.0f * m), bar_height};
  const float top = m;
  const float column = std::max(3.0f, at(PanelId::kPlayback).y - g - top);  // the side columns' height

  // Left: takes (small; warnings scroll inside it) over the parameters, which have the rest.
  const float left_h = column - g;
  // Title, padding, one row per take, a row of load warnings, Frame all and the View header
  // (rows of the 16 px font).
  const float takes_want = 48.0f + 30.0f * static_cast<float>(std::max(takes, 1) + 3);
  const float takes_h = std::clamp(takes_want, 0.18f * left_h, 0.50f * left_h);
  at(PanelId::kTakes) = PanelRect{m, top, side, takes_h};
  at(PanelId::kParameters) = PanelRect{m, top + takes_h + g, side, left_h - takes_h};

  // Right: components over metrics over files. Metrics and files as tall as their rows need
  // (the takes' files, a table row per take); components (a plot that scales) the rest, from 30%
  // to 45% of the column: when that leaves too little, metrics come first (up to 55% of what is
  // left) and the files (whose browser scrolls) have the rest; when it leaves more, the files
  // (their browser) have it.
  const float right_x = width - m - side;
  const float inputs = static_cast<float>(std::max(takes - 1, 1));  // the takes loaded (not the blend)
  const float metrics_want = 44.0f + 24.0f * (inputs + 5.0f);
  const float files_want = 48.0f + 30.0f * (inputs + 4.0f);
  const float right_h = column - 2.0f * g;
  const float components_h = std::clamp(right_h - metrics_want - files_want, 0.30f * right_h, 0.45f * right_h);
  const float metrics_h = std::min(metrics_want, 0.55f * (right_h - components_h));
  at(PanelId::kComponents) = PanelRect{right_x, top, side, components_h};
  at(PanelId::kMetrics) = PanelRect{right_x, top + components_h + g, side, metrics_h};
  at(PanelId::kFiles) = PanelRect{right_x, top + components_h + metrics_h + 2.0f * g, side,
                                  right_h - components_h - metrics_h};

  // Bottom, between the columns: the takes' layers, from just under the clear centre to the bar.
  const float strip_x = m + side + g;
  const float strip_y = std::min(centre.bottom() + g, at(PanelId::kPlayback).y - g - 1.0f);
  at(PanelId::kLayers) = PanelRect{strip_x, strip_y, std::max(1.0f, right_x - g - strip_x),
                                std::max(1.0f, at(PanelId::kPlayback).y - g - strip_y)};
  return r;
}

// The playback bar's height with the current font and style: one row of controls.
inline float playback_bar_height() {
  return ImGui::GetFrameHeight() + 2.0f * ImGui::GetStyle().WindowPadding.y;
}

// The rectangle of `id` for the current display (ImGui's DisplaySize).
inline PanelRect panel_rect(PanelId id, int takes = 3) {
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  return compute_layout(display.x, display.y, playback_bar_height(), takes)[static_cast<size_t>(id)];
}

// Before a panel's ImGui::Begin: its place and size from the layout, forced when
// state.view.reset_layout is set, else only the first time the window appears.
inline void place_panel(PanelId id, const EditorState& state) {
  const PanelRect r = panel_rect(id, static_cast<int>(state.shown.size()));
  const ImGuiCond cond = state.view.reset_layout ? ImGuiCond_Always : ImGuiCond_FirstUseEver;
  ImGui::SetNextWindowPos(ImVec2(r.x, r.y), cond);
  ImGui::SetNextWindowSize(ImVec2(r.w, r.h), cond);
}

// Once per frame, before the panels: sets state.view.reset_layout when ImGui's display size
// differs from *last (the size of the previous frame; start it at zero so that the first frame
// lays the panels out too), so that panels follow a resized window, or when the number of takes
// changed (the Takes panel's height follows it).
inline void track_display_size(EditorState& state, glm::vec2* last) {
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  const int takes = static_cast<int>(state.shown.size());
  if (takes != state.view.laid_out_takes) {
    state.view.reset_layout = true;
    state.view.laid_out_takes = takes;
  }
  if (display.x != last->x || display.y != last->y) {
    state.view.reset_layout = true;
    *last = glm::vec2(display.x, display.y);
  }
}

}  // namespace mostyle::ui
