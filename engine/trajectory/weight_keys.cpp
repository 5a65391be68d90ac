#include "engine/trajectory/weight_keys.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "engine/base/error.h"
#include "engine/kinematics/ease.h"

namespace mostyle {
namespace {

std::string key_name(size_t k, double seconds) {
  char s[64];
  std::snprintf(s, sizeof s, "key %zu (at %g s)", k + 1, seconds);
  return s;
}

}  // namespace

void validate_keys(const WeightKeys& keys, int takes) {
  for (size_t k = 0; k < keys.size(); ++k) {
    const WeightKey& key = keys[k];
    if (!std::isfinite(key.seconds) || key.seconds < 0.0)
      throw InputError("expected key " + std::to_string(k + 1) + "'s time in seconds from 0 up, found " +
                       std::to_string(key.seconds));
    if (k > 0 && !(key.seconds > keys[k - 1].seconds))
      throw InputError("expected keys in order of time: " + key_name(k, key.seconds) + " does not come after " +
                       key_name(k - 1, keys[k - 1].seconds));
    if (static_cast<int>(key.weights.size()) != takes)
      throw InputError("expected " + std::to_string(takes) + " weights, one per take, in " +
                       key_name(k, key.seconds) + ", found " + std::to_string(key.weights.size()));
  }
}

void weights_at(const WeightKeys& keys, double seconds, std::vector<double>& out) {
  const size_t n = keys.front().weights.size();
  out.resize(n);
  // The first key after `seconds`.
  const auto after = std::upper_bound(keys.begin(), keys.end(), seconds,
                                      [](double t, const WeightKey& key) { return t < key.seconds; });
  if (after == keys.begin() || after == keys.end()) {
    const std::vector<double>& held = after == keys.begin() ? keys.front().weights : keys.back().weights;
    std::copy(held.begin(), held.end(), out.begin());
    return;
  }
  const WeightKey& a = *std::prev(after);
  const WeightKey& b = *after;
  const double f = smoothstep((seconds - a.seconds) / (b.seconds - a.seconds));
  for (size_t i = 0; i < n; ++i) out[i] = (1.0 - f) * a.weights[i] + f * b.weights[i];
}

void weights_over_frames(const WeightKeys& keys, Eigen::Index frames, double fps, Eigen::MatrixXd& out) {
  const Eigen::Index n = static_cast<Eigen::Index>(keys.front().weights.size());
  out.resize(frames, n);
  size_t next = 0;  // the first key after the frame's time
  for (Eigen::Index f = 0; f < frames; ++f) {
    const double t = double(f) / fps;
    while (next < keys.size() && keys[next].seconds <= t) ++next;
    if (next == 0 || next == keys.size()) {
      const std::vector<double>& held = next == 0 ? keys.front().weights : keys.back().weights;
      for (Eigen::Index i = 0; i < n; ++i) out(f, i) = held[static_cast<size_t>(i)];
      continue;
    }
    const WeightKey& a = keys[next - 1];
    const WeightKey& b = keys[next];
    const double s = smoothstep((t - a.seconds) / (b.seconds - a.seconds));
    for (Eigen::Index i = 0; i < n; ++i)
      out(f, i) = (1.0 - s) * a.weights[static_cast<size_t>(i)] + s * b.weights[static_cast<size_t>(i)];
  }
}

}  // namespace mostyle
