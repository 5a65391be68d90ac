#pragma once
// The editor in a GLFW window (OpenGL 3.3 core through libGL).
#include "app/editor/editor_options.h"

namespace mostyle::app {

// Opens the window and runs the editor until it is closed, or, with options.screenshot_path,
// for a few frames and writes the PNG. Returns the exit status: 0, or 1 with one line on
// stderr when there is no display or the screenshot cannot be written.
int run_window(const EditorOptions& options);

}  // namespace mostyle::app
