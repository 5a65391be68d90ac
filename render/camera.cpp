#include "render/camera.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace mostyle::render {
namespace {
constexpr float kOrbitRadiansPerPixel = 0.008f;
constexpr float kMaxPitch = 1.53f;      // just under 90 degrees: the view never flips
constexpr float kZoomPerStep = 0.88f;   // distance factor per wheel step
constexpr float kMinDistanceFactor = 0.05f;  // zoom limits, times the framed radius
constexpr float kMaxDistanceFactor = 60.0f;
}  // namespace

ScreenPoint project_to_pixels(const glm::mat4& view_projection, const glm::vec3& world,
                              const glm::ivec2& viewport) {
  ScreenPoint out;
  glm::vec4 clip = view_projection * glm::vec4(world, 1.0f);
  if (clip.w <= 0.0f) return out;
  glm::vec3 ndc = glm::vec3(clip) / clip.w;
  out.pixel.x = (ndc.x * 0.5f + 0.5f) * static_cast<float>(viewport.x);
  out.pixel.y = (1.0f - (ndc.y * 0.5f + 0.5f)) * static_cast<float>(viewport.y);
  out.depth = ndc.z * 0.5f + 0.5f;
  out.visible = std::abs(ndc.x) <= 1.0f && std::abs(ndc.y) <= 1.0f && std::abs(ndc.z) <= 1.0f;
  return out;
}

glm::vec3 OrbitCamera::eye() const {
  glm::vec3 offset(std::cos(pitch) * std::sin(yaw), std::sin(pitch), std::cos(pitch) * std::cos(yaw));
  return target + distance * offset;
}

glm::vec3 OrbitCamera::forward() const { return glm::normalize(target - eye()); }

glm::vec3 OrbitCamera::right() const {
  // Horizontal by construction: pitch never reaches +-90 degrees.
  return glm::vec3(std::cos(yaw), 0.0f, -std::sin(yaw));
}

glm::vec3 OrbitCamera::up() const { return glm::cross(right(), forward()); }

glm::mat4 OrbitCamera::view() const { return glm::lookAt(eye(), target, glm::vec3(0, 1, 0)); }

glm::mat4 OrbitCamera::projection(float aspect) const {
  float near_plane = std::max(distance * 0.01f, scene_radius_ * 1e-4f);
  float far_plane = std::max(distance, scene_radius_) * 200.0f;
  const glm::mat4 shift = glm::translate(glm::mat4(1.0f), glm::vec3(lens_shift, 0.0f));
  return shift * glm::perspective(fov_y, std::max(aspect, 1e-3f), near_plane, far_plane);
}

void OrbitCamera::frame(const Bounds& b, float aspect, float fill) {
  if (b.empty()) return;
  target = b.center();
  scene_radius_ = std::max(b.radius(), 1e-6f);
  // A corner c (relative to the target) at camera coordinates (x, y) and depth d + z is in
  // view when |x| <= tan_x * (d + z) and |y| <= tan_y * (d + z): solve each for d.
  const float tan_y = std::tan(0.5f * fov_y) * std::clamp(fill, 0.05f, 1.0f);
  const float tan_x = tan_y * std::max(aspect, 1e-3f);
  const glm::vec3 r = right(), u = up(), f = forward();
  float needed = 0.0f;
  for (int i = 0; i < 8; ++i) {
    glm::vec3 c = glm::vec3(i & 1 ? b.max.x : b.min.x, i & 2 ? b.max.y : b.min.y, i & 4 ? b.max.z : b.min.z) - target;
    float z = glm::dot(c, f);
    needed = std::max(needed, std::abs(glm::dot(c, r)) / tan_x - z);
    needed = std::max(needed, std::abs(glm::dot(c, u)) / tan_y - z);
  }
  distance = std::max(needed, 1e-3f * scene_radius_);
}

void OrbitCamera::orbit(float dx_pixels, float dy_pixels) {
  yaw -= dx_pixels * kOrbitRadiansPerPixel;
  pitch = std::clamp(pitch + dy_pixels * kOrbitRadiansPerPixel, kMinPitch, kMaxPitch);
  keep_above_floor();
}

void OrbitCamera::keep_above_floor() {
  // eye.y = target.y + distance * sin(pitch) >= distance * sin(kMinPitch): with the target on or
  // above the floor the pitch limit alone does it; a target panned below the floor needs more.
  const float clearance = distance * std::sin(kMinPitch);
  const float needed = (clearance - target.y) / std::max(distance, 1e-6f);  // sin of the lowest pitch
  const float lowest = needed >= std::sin(kMaxPitch) ? kMaxPitch : std::asin(std::max(needed, -1.0f));
  pitch = std::clamp(pitch, std::max(lowest, kMinPitch), kMaxPitch);
  const float eye_height = target.y + distance * std::sin(pitch);
  if (eye_height < clearance) target.y += clearance - eye_height;  // even looking straight down
}

void OrbitCamera::pan(float dx_pixels, float dy_pixels, float viewport_height) {
  float world_per_pixel = 2.0f * distance * std::tan(fov_y * 0.5f) / std::max(viewport_height, 1.0f);
  target += world_per_pixel * (-dx_pixels * right() + dy_pixels * up());
  keep_above_floor();
}

void OrbitCamera::zoom(float wheel_steps) {
  distance *= std::pow(kZoomPerStep, wheel_steps);
  distance = std::clamp(distance, kMinDistanceFactor * scene_radius_, kMaxDistanceFactor * scene_radius_);
  keep_above_floor();
}

void OrbitCamera::follow(const glm::vec3& point, float dt_s, float half_life_s) {
  float t = half_life_s <= 0.0f ? 1.0f : 1.0f - std::exp2(-dt_s / half_life_s);
  target.x += (point.x - target.x) * t;
  target.z += (point.z - target.z) * t;
}

}  // namespace mostyle::render
