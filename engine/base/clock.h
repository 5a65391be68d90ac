#pragma once
// Wall time for stage timings (base/stage_times.h), reports and the editor's metrics.
#include <chrono>

namespace mostyle {

// Milliseconds (fractional) from t0 to now on the steady clock: never negative, unaffected by
// changes of the system's time.
inline double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace mostyle
