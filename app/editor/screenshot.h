#pragma once
// The screenshot protocol both platforms follow, so their PNGs match.
#include <string>

#include <glm/glm.hpp>

#include "app/editor/editor.h"

namespace mostyle::app {

// Frames rendered before the picture is taken: ImGui sizes auto-fitting windows over the
// first two frames; one more for good measure.
constexpr int kScreenshotFrames = 4;
// The fixed time step of screenshot frames (the playhead does not move in them anyway).
constexpr float kScreenshotDeltaS = 1.0f / 60.0f;

// Reads framebuffer 0 (the window's back buffer or the OSMesa buffer) and writes it to
// `path`. Returns 0, or 1 after printing "mostyle: PATH: cannot write PNG ..." on stderr.
int write_screenshot(const glm::ivec2& size, const std::string& path);

}  // namespace mostyle::app
