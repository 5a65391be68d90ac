#pragma once
// An RGBA8 image in memory (rows top to bottom), and reading one back from the GL framebuffer.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace mostyle::render {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;  // width * height * 4 bytes, row 0 at the top

  bool empty() const { return width <= 0 || height <= 0; }
  // Pixel (x right, y down from the top-left). Asserts it is inside.
  glm::u8vec4 at(int x, int y) const;
};

// Reads `size` pixels from (0, 0) of the bound read framebuffer (the back buffer of a window,
// the OSMesa buffer, or a single-sample FBO) and flips them so row 0 is the top. Needs a current
// GL context. O(width * height). opaque: set every alpha to 255 (a window has no transparency).
Image read_framebuffer(const glm::ivec2& size, bool opaque = true);

}  // namespace mostyle::render
