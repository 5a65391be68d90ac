#include "tests/render/osmesa_context.h"

#include "render/gl.h"
#include <GL/osmesa.h>

namespace mostyle::test {

OsMesaContext::OsMesaContext(const glm::ivec2& size) : size_(size) {
  const int attributes[] = {OSMESA_FORMAT, OSMESA_RGBA,
                            OSMESA_DEPTH_BITS, 24,
                            OSMESA_STENCIL_BITS, 8,
                            OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                            OSMESA_CONTEXT_MAJOR_VERSION, 3,
                            OSMESA_CONTEXT_MINOR_VERSION, 3,
                            0};
  OSMesaContext context = OSMesaCreateContextAttribs(attributes, nullptr);
  if (context == nullptr) {
    error_ = "OSMesaCreateContextAttribs failed (core 3.3)";
    return;
  }
  buffer_.assign(static_cast<size_t>(size.x) * static_cast<size_t>(size.y) * 4, 0);
  if (!OSMesaMakeCurrent(context, buffer_.data(), GL_UNSIGNED_BYTE, size.x, size.y)) {
    OSMesaDestroyContext(context);
    error_ = "OSMesaMakeCurrent failed";
    return;
  }
  context_ = context;
}

OsMesaContext::~OsMesaContext() {
  if (context_ != nullptr) OSMesaDestroyContext(static_cast<OSMesaContext>(context_));
}

}  // namespace mostyle::test
