#pragma once
// Sliders over a document field's range (ui/model/document_fields.h): the slider's ends are the
// range's, and a value typed in (Ctrl+click) is clamped to it too, so a field never holds what a
// session file would refuse.
#include <imgui.h>

#include "ui/model/document_fields.h"

namespace mostyle::ui {

inline bool range_slider(const char* label, double& v, const Range& r, const char* format = "%.2f") {
  float f = static_cast<float>(v);
  if (!ImGui::SliderFloat(label, &f, static_cast<float>(r.lo), static_cast<float>(r.hi), format,
                          ImGuiSliderFlags_AlwaysClamp))
    return false;
  v = f;
  return true;
}

// Shown from `shown_from` (1: the levels as the panel counts them), stored from r.lo.
inline bool range_slider(const char* label, int& v, const Range& r, const char* format = "%d", int shown_from = 0) {
  const int lo = static_cast<int>(r.lo), hi = static_cast<int>(r.hi);
  int shown = v - lo + shown_from;
  if (!ImGui::SliderInt(label, &shown, shown_from, hi - lo + shown_from, format, ImGuiSliderFlags_AlwaysClamp))
    return false;
  v = shown - shown_from + lo;
  return true;
}

}  // namespace mostyle::ui
