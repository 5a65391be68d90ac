#include "render/ground_renderer.h"

#include <catch2/catch.hpp>

#include "tests/render/osmesa_context.h"
#include "tests/render/pixel_checks.h"
#include "tests/render/scene_fixtures.h"

using namespace mostyle::render;
using namespace mostyle::test;

namespace {
// Looking down at the floor in front of the skeleton.
OrbitCamera floor_camera() {
  OrbitCamera camera;
  camera.target = glm::vec3(0.0f, 0.0f, 0.6f);
  camera.pitch = 0.7f;
  camera.distance = 3.0f;
  return camera;
}
}  // namespace

TEST_CASE("auto_grid_spacing is a power of ten a quarter of the size or less") {
  CHECK(auto_grid_spacing(170.0f) == Approx(10.0f));
  CHECK(auto_grid_spacing(30.0f) == Approx(1.0f));
  CHECK(auto_grid_spacing(1.7f) == Approx(0.1f));
  CHECK(auto_grid_spacing(0.0f) == 1.0f);
}

TEST_CASE("the floor shows grid lines where the grid says, ground between them") {
  OsMesaContext gl(kTestSize);
  REQUIRE(gl.ok());
  SceneRenderer renderer;
  SceneStyle style = flat_style();
  style.ground.grid_spacing = 0.1f;  // major lines every 1.0
  style.ground.shadows = false;
  OrbitCamera camera = floor_camera();
  Image with_grid = render_image(renderer, Scene{}, camera, style);
  style.ground.grid = false;
  Image without_grid = render_image(renderer, Scene{}, camera, style);

  // On the major line x = 1 (between minor lines in z), and half-way between minor lines.
  const glm::vec3 on_line(1.0f, 0.0f, 0.55f);
  const glm::vec3 off_line(0.95f, 0.0f, 0.55f);
  int on = max_brightness_near(with_grid, camera, on_line, 1);
  int off = brightness(pixel_at(with_grid, camera, off_line));
  INFO("on line " << on << ", between lines " << off);
  CHECK(on > off + 12);
  // Without the grid the same places are plain ground, and the ground is not the background.
  glm::u8vec4 plain = pixel_at(without_grid, camera, on_line);
  CHECK(std::abs(brightness(plain) - off) <= 3);
  CHECK_FALSE(near_color(plain, kFlatBackground, 10));
  // The X axis (z = 0) is tinted red, the Z axis (x = 0) blue.
  glm::u8vec4 x_axis = pixel_at(with_grid, camera, glm::vec3(0.45f, 0.0f, 0.0f));
  glm::u8vec4 z_axis = pixel_at(with_grid, camera, glm::vec3(0.0f, 0.0f, 0.45f));
  INFO("x axis " << describe(x_axis) << ", z axis " << describe(z_axis));
  CHECK(x_axis.r > x_axis.b + 10);
  CHECK(z_axis.b > z_axis.r + 10);
}

TEST_CASE("a skeleton casts a soft contact shadow next to its lowest joint") {
  OsMesaContext gl(kTestSize);
  REQUIRE(gl.ok());
  SceneRenderer renderer;
  Scene scene;
  scene.skeletons = {three_joint_skeleton(kRed)};
  SceneStyle style = flat_style();
  style.ground.grid = false;
  OrbitCamera camera = floor_camera();
  Image shadowed = render_image(renderer, scene, camera, style);
  style.ground.shadows = false;
  Image unshadowed = render_image(renderer, scene, camera, style);
  // In front of the lowest joint (0.2 high), outside its sphere.
  const glm::vec3 beside(0.0f, 0.0f, 0.09f);
  int dark = brightness(pixel_at(shadowed, camera, beside));
  int light = brightness(pixel_at(unshadowed, camera, beside));
  INFO("shadowed " << dark << ", unshadowed " << light);
  CHECK(dark < light - 15);
  // Far from the skeleton there is no shadow.
  const glm::vec3 far(1.2f, 0.0f, 1.0f);
  CHECK(std::abs(brightness(pixel_at(shadowed, camera, far)) - brightness(pixel_at(unshadowed, camera, far))) <= 2);
}

TEST_CASE("a joint flagged in contact gets a ring in its skeleton's colour") {
  OsMesaContext gl(kTestSize);
  REQUIRE(gl.ok());
  SceneRenderer renderer;
  Scene scene;
  SkeletonPose pose = three_joint_skeleton(kBlue);
  pose.positions[0].y = 0.0f;  // the lowest joint on the floor
  scene.skeletons = {pose};
  SceneStyle style = flat_style();
  style.ground.grid = false;
  style.ground.shadows = false;
  OrbitCamera camera = floor_camera();
  Image without = render_image(renderer, scene, camera, style);
  scene.skeletons[0].contacts = {1, 0, 0};
  Image with = render_image(renderer, scene, camera, style);
  // On the ring, in front of the joint (the ring's radius is 0.045 * size = 0.09).
  const glm::vec3 on_ring(0.0f, 0.0f, 0.076f);
  glm::u8vec4 ring = pixel_at(with, camera, on_ring);
  glm::u8vec4 floor = pixel_at(without, camera, on_ring);
  INFO("ring " << describe(ring) << ", floor " << describe(floor));
  CHECK(ring.b > floor.b + 40);
  CHECK(dominated_by(ring, 2));
}
