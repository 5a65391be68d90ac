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

// A drag field over the range, for values whose sign matters and that a narrow slider's knob would
// hide: the value always shows whole, signed ("%+.2f"), `per_pixel` of it per pixel dragged (fine
// however narrow the field), typed after a double-click, clamped to the range.
inline bool range_drag(const char* label, double& v, const Range& r, float per_pixel = 0.005f,
                       const char* format = "%+.2f") {
  float f = static_cast<float>(v);
  if (!ImGui::DragFloat(label, &f, per_pixel, static_cast<float>(r.lo), static_cast<float>(r.hi), format,
                        ImGuiSliderFlags_AlwaysClamp))
    return false;
  v = f;
  return true;
}

// Shown `offset` above what is stored (1: levels stored from 0 and shown from 1).
inline bool range_slider(const char* label, int& v, const Range& r, const char* format = "%d", int offset = 0) {
  const int lo = static_cast<int>(r.lo), hi = static_cast<int>(r.hi);
  int shown = v + offset;
  if (!ImGui::SliderInt(label, &shown, lo + offset, hi + offset, format, ImGuiSliderFlags_AlwaysClamp)) return false;
  v = shown - offset;
  return true;
}

}  // namespace mostyle::ui
