#include "ui/model/weight_keys_edit.h"

#include <algorithm>
#include <cmath>
#include <iterator>

namespace mostyle::ui {
namespace {

// The first key after `seconds` (keys in order of time).
WeightKeys::const_iterator first_after(const WeightKeys& keys, double seconds) {
  return std::upper_bound(keys.begin(), keys.end(), seconds,
                          [](double t, const WeightKey& key) { return t < key.seconds; });
}

}  // namespace

bool same_keys(const WeightKeys& x, const WeightKeys& y) {
  return std::equal(x.begin(), x.end(), y.begin(), y.end(), [](const WeightKey& a, const WeightKey& b) {
    return a.seconds == b.seconds && a.weights == b.weights;
  });
}

bool keys_fit(const WeightKeys& keys, int takes) {
  return !keys.empty() && std::all_of(keys.begin(), keys.end(), [&](const WeightKey& key) {
    return static_cast<int>(key.weights.size()) == takes;
  });
}

int key_near(const WeightKeys& keys, double seconds, double tolerance_s) {
  // The nearest is the last key at or before `seconds` or the first after it.
  const auto after = first_after(keys, seconds);
  int best = -1;
  double best_distance = tolerance_s;
  auto consider = [&](WeightKeys::const_iterator it) {
    const double distance = std::fabs(it->seconds - seconds);
    if (distance <= best_distance) {
      best = static_cast<int>(std::distance(keys.begin(), it));
      best_distance = distance;
    }
  };
  if (after != keys.begin()) consider(std::prev(after));
  if (after != keys.end()) consider(after);
  return best;
}

int set_key(WeightKeys& keys, double seconds, double tolerance_s, std::vector<double> weights) {
  const int at = key_near(keys, seconds, tolerance_s);
  if (at >= 0) {
    keys[static_cast<size_t>(at)].weights = std::move(weights);
    return at;
  }
  const auto after = keys.begin() + std::distance(keys.cbegin(), first_after(keys, seconds));
  return static_cast<int>(std::distance(keys.begin(), keys.insert(after, WeightKey{seconds, std::move(weights)})));
}

double move_key(WeightKeys& keys, int i, double seconds, double gap_s, double length_s) {
  const size_t k = static_cast<size_t>(i);
  const double lo = k > 0 ? keys[k - 1].seconds + gap_s : 0.0;
  const double hi = std::min(k + 1 < keys.size() ? keys[k + 1].seconds - gap_s : length_s, length_s);
  if (lo <= hi) keys[k].seconds = std::clamp(seconds, lo, hi);
  return keys[k].seconds;
}

WeightKeys reorder_keys(const WeightKeys& keys, const std::vector<int>& order) {
  WeightKeys out = keys;
  for (WeightKey& key : out) {
    if (key.weights.size() != order.size()) continue;
    const WeightKey& given = keys[static_cast<size_t>(&key - out.data())];
    for (size_t k = 0; k < order.size(); ++k) key.weights[k] = given.weights[static_cast<size_t>(order[k])];
  }
  return out;
}

}  // namespace mostyle::ui
