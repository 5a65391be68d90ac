#include "render/image.h"

#include <cassert>
#include <cstring>

#include "render/gl.h"

namespace mostyle::render {

glm::u8vec4 Image::at(int x, int y) const {
  assert(x >= 0 && x < width && y >= 0 && y < height);
  const std::uint8_t* p = &rgba[(static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)) * 4];
  return glm::u8vec4(p[0], p[1], p[2], p[3]);
}

Image read_framebuffer(const glm::ivec2& size, bool opaque) {
  Image image;
  if (size.x <= 0 || size.y <= 0) return image;
  image.width = size.x;
  image.height = size.y;
  const size_t row = static_cast<size_t>(size.x) * 4;
  std::vector<std::uint8_t> bottom_up(row * static_cast<size_t>(size.y));
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, size.x, size.y, GL_RGBA, GL_UNSIGNED_BYTE, bottom_up.data());
  image.rgba.resize(bottom_up.size());
  for (int y = 0; y < size.y; ++y) {  // GL's row 0 is the bottom
    std::memcpy(&image.rgba[static_cast<size_t>(y) * row],
                &bottom_up[static_cast<size_t>(size.y - 1 - y) * row], row);
  }
  if (opaque) {
    for (size_t i = 3; i < image.rgba.size(); i += 4) image.rgba[i] = 255;
  }
  return image;
}

}  // namespace mostyle::render
