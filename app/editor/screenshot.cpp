#include "app/editor/screenshot.h"

#include <cstdio>

#include "engine/base/error.h"
#include "render/gl.h"
#include "render/image.h"
#include "render/png_io.h"

namespace mostyle::app {

int write_screenshot(const glm::ivec2& size, const std::string& path) {
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glFinish();
  render::Image image = render::read_framebuffer(size);
  try {
    render::write_png(image, path);
  } catch (const InputError& e) {
    std::fprintf(stderr, "mostyle: %s\n", e.what());
    return 1;
  }
  return 0;
}

}  // namespace mostyle::app
