#pragma once
// The editor with no display: OSMesa (OpenGL 3.3 core, llvmpipe) into memory, ImGui fed its
// display size by us instead of GLFW. Same frames as the window, for screenshots and CI.
#include "app/editor/editor_options.h"

namespace mostyle::app {

// Renders a few frames and writes options.screenshot_path. Returns 0, or 1 with one line on
// stderr when OSMesa fails or the PNG cannot be written.
int run_offscreen(const EditorOptions& options);

}  // namespace mostyle::app
