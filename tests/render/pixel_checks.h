#pragma once
// Small pixel predicates shared by the render tests. Colours are RGBA8 from read_framebuffer().
#include <algorithm>
#include <cstdlib>
#include <sstream>
#include <string>

#include <glm/glm.hpp>

#include "render/camera.h"
#include "render/image.h"

namespace mostyle::test {

// How far a channel must lead the other two for a pixel to count as "that colour".
constexpr int kDominanceMargin = 30;
// Per-channel tolerance for a flat colour (8-bit rounding, dithering-free llvmpipe).
constexpr int kFlatTolerance = 3;

inline std::string describe(const glm::u8vec4& c) {
  std::ostringstream s;
  s << "rgb(" << int(c.r) << ", " << int(c.g) << ", " << int(c.b) << ")";
  return s.str();
}

// channel 0 = red, 1 = green, 2 = blue.
inline bool dominated_by(const glm::u8vec4& c, int channel) {
  int v[3] = {c.r, c.g, c.b};
  for (int i = 0; i < 3; ++i) {
    if (i != channel && v[channel] < v[i] + kDominanceMargin) return false;
  }
  return true;
}

inline bool near_color(const glm::u8vec4& c, const glm::vec3& srgb, int tolerance = kFlatTolerance) {
  glm::ivec3 expected = glm::ivec3(glm::round(srgb * 255.0f));
  return std::abs(c.r - expected.r) <= tolerance && std::abs(c.g - expected.g) <= tolerance &&
         std::abs(c.b - expected.b) <= tolerance;
}

inline int brightness(const glm::u8vec4& c) { return c.r + c.g + c.b; }

// Pixel under a world point, rounded to the pixel that contains its projection.
inline glm::ivec2 pixel_of(const render::OrbitCamera& camera, const glm::vec3& world, const glm::ivec2& size) {
  float aspect = static_cast<float>(size.x) / static_cast<float>(size.y);
  render::ScreenPoint p = render::project_to_pixels(camera.view_projection(aspect), world, size);
  return glm::ivec2(glm::floor(p.pixel));
}

inline glm::u8vec4 pixel_at(const render::Image& image, const render::OrbitCamera& camera, const glm::vec3& world) {
  glm::ivec2 p = pixel_of(camera, world, {image.width, image.height});
  p = glm::clamp(p, glm::ivec2(0), glm::ivec2(image.width - 1, image.height - 1));
  return image.at(p.x, p.y);
}

// Brightest pixel within `radius` pixels of the projection of `world`.
inline int max_brightness_near(const render::Image& image, const render::OrbitCamera& camera,
                               const glm::vec3& world, int radius) {
  glm::ivec2 p = pixel_of(camera, world, {image.width, image.height});
  int best = 0;
  for (int y = p.y - radius; y <= p.y + radius; ++y) {
    for (int x = p.x - radius; x <= p.x + radius; ++x) {
      if (x >= 0 && y >= 0 && x < image.width && y < image.height) best = std::max(best, brightness(image.at(x, y)));
    }
  }
  return best;
}

}  // namespace mostyle::test
