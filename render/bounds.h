#pragma once
// An axis-aligned box in world units, grown point by point. Empty until the first point.
#include <algorithm>
#include <limits>

#include <glm/glm.hpp>

namespace mostyle::render {

struct Bounds {
  glm::vec3 min{std::numeric_limits<float>::max()};
  glm::vec3 max{std::numeric_limits<float>::lowest()};

  bool empty() const { return min.x > max.x; }
  void extend(const glm::vec3& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  void extend(const Bounds& b) {
    if (!b.empty()) {
      extend(b.min);
      extend(b.max);
    }
  }
  glm::vec3 center() const { return empty() ? glm::vec3(0.0f) : 0.5f * (min + max); }
  glm::vec3 extent() const { return empty() ? glm::vec3(0.0f) : max - min; }
  // Radius of the sphere around center() that holds the box; 0 when empty.
  float radius() const { return empty() ? 0.0f : 0.5f * glm::length(max - min); }
};

}  // namespace mostyle::render
