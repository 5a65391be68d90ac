#include "render/render_target.h"

#include <algorithm>

namespace mostyle::render {

RenderTarget::~RenderTarget() { release(); }

void RenderTarget::release() {
  if (framebuffer_ != 0) glDeleteFramebuffers(1, &framebuffer_);
  if (color_ != 0) glDeleteRenderbuffers(1, &color_);
  if (depth_ != 0) glDeleteRenderbuffers(1, &depth_);
  framebuffer_ = color_ = depth_ = 0;
  size_ = glm::ivec2(0);
  samples_ = 0;
}

bool RenderTarget::resize(const glm::ivec2& size, int samples) {
  GLint max_samples = 1;
  glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
  samples = std::clamp(samples, 1, std::max(max_samples, 1));
  if (framebuffer_ != 0 && size == size_ && samples == samples_) return true;
  release();
  if (size.x <= 0 || size.y <= 0) return false;

  GLint previous = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previous);
  // One sample means plain storage: multisampled renderbuffers with 1 sample are allowed but
  // some drivers treat them as multisampled for blits, which then cannot scale.
  const GLsizei storage_samples = samples > 1 ? samples : 0;
  glGenRenderbuffers(1, &color_);
  glBindRenderbuffer(GL_RENDERBUFFER, color_);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, storage_samples, GL_RGBA8, size.x, size.y);
  glGenRenderbuffers(1, &depth_);
  glBindRenderbuffer(GL_RENDERBUFFER, depth_);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, storage_samples, GL_DEPTH_COMPONENT24, size.x, size.y);
  glBindRenderbuffer(GL_RENDERBUFFER, 0);
  glGenFramebuffers(1, &framebuffer_);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer_);
  glFramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color_);
  glFramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
  const bool complete = glCheckFramebufferStatus(GL_DRAW_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(previous));
  if (!complete) {
    release();
    return false;
  }
  size_ = size;
  samples_ = samples;
  return true;
}

void RenderTarget::bind() const { glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_); }

void RenderTarget::resolve_to(GLuint destination, const glm::ivec2& destination_size) const {
  glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, destination);
  glDisable(GL_SCISSOR_TEST);
  // A multisample resolve must not scale; scale in a second step only if ever needed.
  glBlitFramebuffer(0, 0, size_.x, size_.y, 0, 0, destination_size.x, destination_size.y,
                    GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_FRAMEBUFFER, destination);
}

}  // namespace mostyle::render
