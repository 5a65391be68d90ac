#include "render/gpu_timer.h"

namespace mostyle::render {

GpuTimer::~GpuTimer() {
  if (created_) glDeleteQueries(kRing, queries_.data());
}

void GpuTimer::begin() {
  if (!created_) {
    glGenQueries(kRing, queries_.data());
    created_ = true;
  }
  // Collect whatever finished; a query still in flight is skipped, never waited for.
  for (int i = 0; i < kRing; ++i) {
    if (!pending_[i]) continue;
    GLint available = 0;
    glGetQueryObjectiv(queries_[i], GL_QUERY_RESULT_AVAILABLE, &available);
    if (!available) continue;
    // 32 bits of nanoseconds (4 s) hold any frame; libOSMesa does not export the 64-bit getter.
    GLuint ns = 0;
    glGetQueryObjectuiv(queries_[i], GL_QUERY_RESULT, &ns);
    pending_[i] = false;
    const float ms = static_cast<float>(static_cast<double>(ns) * 1e-6);
    smoothed_ms_ = smoothed_ms_ == 0.0f ? ms : smoothed_ms_ + (ms - smoothed_ms_) * 0.05f;
  }
  if (pending_[next_]) return;  // ring full: skip this measurement
  glBeginQuery(GL_TIME_ELAPSED, queries_[next_]);
  pending_[next_] = true;
  active_ = true;
}

void GpuTimer::end() {
  if (!active_) return;
  glEndQuery(GL_TIME_ELAPSED);
  active_ = false;
  next_ = (next_ + 1) % kRing;
}

}  // namespace mostyle::render
