#pragma once
// The editor's look: a dark neutral ImGui style that sits on the viewport's background, and
// the UI font. Call once after ImGui::CreateContext(), before the first frame.
namespace mostyle::ui {

void apply_theme();

// Loads DejaVu Sans (or another packaged sans-serif TTF) at `pixel_size`; falls back to
// ImGui's built-in font when none is installed. Returns the file used, or "" for the built-in.
const char* load_fonts(float pixel_size = 16.0f);

}  // namespace mostyle::ui
