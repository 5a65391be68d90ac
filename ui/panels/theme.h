#pragma once
// The editor's look: a dark neutral ImGui style that sits on the viewport's background, the
// colours the panels' sentences take, and the UI font. Call apply_theme once after
// ImGui::CreateContext(), before the first frame.
#include <imgui.h>

namespace mostyle::ui {

// Text: an error, a hint or a value of less weight, a success, a warning.
inline const ImVec4 kErrorColor(1.0f, 0.45f, 0.40f, 1.0f);
inline const ImVec4 kDimColor(0.60f, 0.62f, 0.66f, 1.0f);
inline const ImVec4 kOkColor(0.55f, 0.85f, 0.55f, 1.0f);
inline const ImVec4 kWarningColor(0.95f, 0.78f, 0.35f, 1.0f);

// Style over time: a key's mark on the timeline (amber, as animation tools draw keys), and the
// frame of a weight control that keys (ui/panels/keyed_tint.h): a key at the playhead (amber), or
// keyed with none there (green: the value eased between keys).
inline const ImVec4 kKeyColor(0.98f, 0.74f, 0.24f, 1.0f);
inline const ImVec4 kOnKeyFrameColor(0.46f, 0.38f, 0.14f, 1.0f);
inline const ImVec4 kKeyedFrameColor(0.20f, 0.34f, 0.20f, 1.0f);

void apply_theme();

// Loads DejaVu Sans (or another packaged sans-serif TTF) at `pixel_size`; falls back to
// ImGui's built-in font when none is installed. Returns the file used, or "" for the built-in.
const char* load_fonts(float pixel_size = 16.0f);

}  // namespace mostyle::ui
