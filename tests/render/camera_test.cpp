#include "render/camera.h"

#include <cmath>

#include <catch2/catch.hpp>

using mostyle::render::Bounds;
using mostyle::render::OrbitCamera;
using mostyle::render::project_to_pixels;
using mostyle::render::ScreenPoint;

namespace {
constexpr float kPixelTolerance = 0.05f;  // float round-off, in pixels
const glm::ivec2 kViewport(1280, 720);
constexpr float kAspect = 1280.0f / 720.0f;

Bounds box(const glm::vec3& lo, const glm::vec3& hi) {
  Bounds b;
  b.extend(lo);
  b.extend(hi);
  return b;
}

std::vector<glm::vec3> corners(const Bounds& b) {
  std::vector<glm::vec3> out;
  for (int i = 0; i < 8; ++i)
    out.emplace_back(i & 1 ? b.max.x : b.min.x, i & 2 ? b.max.y : b.min.y, i & 4 ? b.max.z : b.min.z);
  return out;
}
}  // namespace

TEST_CASE("project_to_pixels maps the target to the viewport centre and y downwards") {
  OrbitCamera camera;
  camera.target = glm::vec3(1, 2, 3);
  camera.distance = 5.0f;
  glm::mat4 vp = camera.view_projection(kAspect);
  ScreenPoint centre = project_to_pixels(vp, camera.target, kViewport);
  REQUIRE(centre.visible);
  CHECK(centre.pixel.x == Approx(640.0f).margin(kPixelTolerance));
  CHECK(centre.pixel.y == Approx(360.0f).margin(kPixelTolerance));
  // Up in the world is up on screen (smaller y); +X is to the right at yaw 0.
  CHECK(project_to_pixels(vp, camera.target + glm::vec3(0, 1, 0), kViewport).pixel.y < 360.0f);
  CHECK(project_to_pixels(vp, camera.target + glm::vec3(1, 0, 0), kViewport).pixel.x > 640.0f);
  // Behind the camera: not visible.
  CHECK_FALSE(project_to_pixels(vp, camera.eye() - camera.forward(), kViewport).visible);
}

TEST_CASE("frame() fits the box whatever the units") {
  for (float unit : {1.0f, 17.0f, 100.0f}) {
    CAPTURE(unit);
    Bounds b = box(glm::vec3(-0.3f, 0.0f, -0.2f) * unit, glm::vec3(0.3f, 1.8f, 0.2f) * unit);
    OrbitCamera camera;
    camera.yaw = 0.6f;
    camera.pitch = 0.3f;
    camera.frame(b, kAspect);
    CHECK(camera.target.y == Approx(0.9f * unit));
    glm::mat4 vp = camera.view_projection(kAspect);
    for (const glm::vec3& c : corners(b)) {
      ScreenPoint p = project_to_pixels(vp, c, kViewport);
      CHECK(p.visible);
    }
    // Scale-free: the same box in other units lands on the same pixels.
    OrbitCamera reference;
    reference.yaw = 0.6f;
    reference.pitch = 0.3f;
    reference.frame(box(glm::vec3(-0.3f, 0.0f, -0.2f), glm::vec3(0.3f, 1.8f, 0.2f)), kAspect);
    glm::mat4 reference_vp = reference.view_projection(kAspect);
    for (const glm::vec3& c : corners(b)) {
      ScreenPoint p = project_to_pixels(vp, c, kViewport);
      ScreenPoint q = project_to_pixels(reference_vp, c / unit, kViewport);
      CHECK(p.pixel.x == Approx(q.pixel.x).margin(0.01f));
      CHECK(p.pixel.y == Approx(q.pixel.y).margin(0.01f));
    }
  }
}

TEST_CASE("frame() ignores an empty box") {
  OrbitCamera camera;
  camera.distance = 7.0f;
  camera.frame(Bounds{}, kAspect);
  CHECK(camera.distance == 7.0f);
}

TEST_CASE("orbit turns around the target at a fixed distance, pitch stops short of the pole") {
  OrbitCamera camera;
  camera.target = glm::vec3(0, 1, 0);
  camera.distance = 4.0f;
  camera.orbit(100.0f, 0.0f);
  CHECK(glm::length(camera.eye() - camera.target) == Approx(4.0f));
  CHECK(camera.yaw < 0.0f);
  camera.orbit(0.0f, 100000.0f);
  CHECK(camera.pitch < 1.5708f);
  CHECK(std::isfinite(camera.view()[0][0]));
  camera.orbit(0.0f, -200000.0f);
  CHECK(camera.pitch > -1.5708f);
}

TEST_CASE("pan keeps the point under the cursor under the cursor") {
  OrbitCamera camera;
  camera.yaw = 0.4f;
  camera.pitch = 0.2f;
  camera.distance = 3.0f;
  glm::vec3 anchor = camera.target;
  camera.pan(50.0f, -30.0f, static_cast<float>(kViewport.y));
  ScreenPoint p = project_to_pixels(camera.view_projection(kAspect), anchor, kViewport);
  CHECK(p.pixel.x == Approx(640.0f + 50.0f).margin(0.5f));
  CHECK(p.pixel.y == Approx(360.0f - 30.0f).margin(0.5f));
}

TEST_CASE("zoom scales the distance within limits set by the framed size") {
  OrbitCamera camera;
  camera.frame(box(glm::vec3(0.0f), glm::vec3(1.0f)), kAspect);
  float d = camera.distance;
  camera.zoom(1.0f);
  CHECK(camera.distance < d);
  camera.zoom(-2.0f);
  CHECK(camera.distance > d);
  camera.zoom(1000.0f);
  float nearest = camera.distance;
  CHECK(nearest > 0.0f);
  CHECK(nearest >= 0.01f * camera.scene_radius());
  camera.zoom(-1000.0f);
  CHECK(camera.distance <= 100.0f * camera.scene_radius());
}

TEST_CASE("follow halves the horizontal gap per half-life and keeps the height") {
  OrbitCamera camera;
  camera.target = glm::vec3(0.0f, 1.0f, 0.0f);
  camera.follow(glm::vec3(8.0f, 5.0f, -4.0f), 0.25f, 0.25f);
  CHECK(camera.target.x == Approx(4.0f));
  CHECK(camera.target.z == Approx(-2.0f));
  CHECK(camera.target.y == 1.0f);
  camera.follow(glm::vec3(8.0f, 5.0f, -4.0f), 1.0f, 0.0f);  // no smoothing: snaps
  CHECK(camera.target.x == Approx(8.0f));
}

TEST_CASE("no gesture puts the eye under the floor") {
  OrbitCamera camera;
  camera.frame(box(glm::vec3(-0.3f, 0.0f, -0.2f), glm::vec3(0.3f, 1.8f, 0.2f)), kAspect);
  // Dragging up as far as it goes: the eye stops a few degrees above the horizon.
  camera.orbit(0.0f, -100000.0f);
  CHECK(camera.pitch == Approx(OrbitCamera::kMinPitch));
  CHECK(camera.eye().y > 0.0f);
  // Zoomed right in and out, and panned down below the floor, still above it.
  for (float steps : {40.0f, -80.0f}) {
    camera.zoom(steps);
    CHECK(camera.eye().y >= camera.distance * std::sin(OrbitCamera::kMinPitch) * 0.999f);
  }
  for (int i = 0; i < 50; ++i) {
    camera.pan(0.0f, -400.0f, static_cast<float>(kViewport.y));
    camera.orbit(0.0f, -400.0f);
    CHECK(camera.eye().y > 0.0f);
    CHECK(camera.pitch <= 1.5708f);
  }
  // Dragging down still looks from above, short of the pole.
  camera.orbit(0.0f, 100000.0f);
  CHECK(camera.eye().y > 0.0f);
  CHECK(camera.pitch < 1.5708f);
}
