#pragma once
// An offscreen multisampled colour + depth framebuffer. The viewport draws into it and
// resolves into the window's (or OSMesa's) framebuffer, so edges are smooth in both, and the
// window and an offscreen screenshot show the same pixels. Needs a current GL context for
// every call and for destruction.
#include <glm/glm.hpp>

#include "render/gl.h"

namespace mostyle::render {

class RenderTarget {
 public:
  RenderTarget() = default;
  ~RenderTarget();
  RenderTarget(const RenderTarget&) = delete;
  RenderTarget& operator=(const RenderTarget&) = delete;

  // (Re)allocates storage when the size or sample count changed; samples is clamped to
  // [1, GL_MAX_SAMPLES]. Returns false (and keeps nothing) if the framebuffer is incomplete.
  bool resize(const glm::ivec2& size, int samples);
  // Binds it for drawing; the caller draws with the viewport set to size().
  void bind() const;
  // Resolves (and scales if sizes differ) the colour into framebuffer `destination` (0: the
  // default one) at (0, 0, destination_size), and leaves `destination` bound for drawing.
  void resolve_to(GLuint destination, const glm::ivec2& destination_size) const;

  glm::ivec2 size() const { return size_; }
  int samples() const { return samples_; }
  GLuint framebuffer() const { return framebuffer_; }

 private:
  void release();
  GLuint framebuffer_ = 0, color_ = 0, depth_ = 0;
  glm::ivec2 size_{0};
  int samples_ = 0;
};

}  // namespace mostyle::render
