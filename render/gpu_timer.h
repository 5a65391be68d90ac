#pragma once
// How long the GPU (or llvmpipe) takes over a stretch of GL commands, read a few frames later
// so it never stalls the pipeline: GL_TIME_ELAPSED queries in a small ring. Needs a current
// GL context for every call and for destruction.
#include <array>

#include "render/gl.h"

namespace mostyle::render {

class GpuTimer {
 public:
  GpuTimer() = default;
  ~GpuTimer();
  GpuTimer(const GpuTimer&) = delete;
  GpuTimer& operator=(const GpuTimer&) = delete;

  // Brackets the commands to time; no nesting with other GL_TIME_ELAPSED queries.
  void begin();
  void end();
  // The latest finished measurement, in milliseconds (smoothed over ~20 readings); 0 until
  // the first one is in.
  float milliseconds() const { return smoothed_ms_; }

 private:
  static constexpr int kRing = 4;
  std::array<GLuint, kRing> queries_{};
  std::array<bool, kRing> pending_{};
  int next_ = 0;
  bool created_ = false;
  bool active_ = false;  // begin() started a query that end() must close
  float smoothed_ms_ = 0.0f;
};

}  // namespace mostyle::render
