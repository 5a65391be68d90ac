#pragma once
// Easing shared by the stages that fade one thing into another: a take's posture into its own
// frames (align/cycle_registration), weights between keys (trajectory/weight_keys), the foot lock's
// offsets over a swing (post/foot_lock).
#include <algorithm>

namespace mostyle {

// 3x^2 - 2x^3 of x clamped to [0, 1]: 0 at 0, 1 at 1, flat at both ends (no kink where an ease
// begins or ends).
inline double smoothstep(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3.0 - 2.0 * x);
}

}  // namespace mostyle
