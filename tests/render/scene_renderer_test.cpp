#include "render/scene_renderer.h"

#include <catch2/catch.hpp>

#include "tests/render/osmesa_context.h"
#include "tests/render/pixel_checks.h"
#include "tests/render/scene_fixtures.h"

using namespace mostyle::render;
using namespace mostyle::test;

TEST_CASE("a three-joint skeleton is drawn in its colour at its projected joints") {
  OsMesaContext gl(kTestSize);
  REQUIRE(gl.ok());
  SceneRenderer renderer;
  Scene scene;
  scene.skeletons = {three_joint_skeleton(kRed)};
  OrbitCamera camera = front_camera();
  Image image = render_image(renderer, scene, camera, flat_style());
  REQUIRE(image.width == kTestSize.x);
  REQUIRE(image.height == kTestSize.y);

  for (const glm::vec3& joint : scene.skeletons[0].positions) {
    glm::u8vec4 c = pixel_at(image, camera, joint);
    INFO("joint at y = " << joint.y << ": " << describe(c));
    CHECK(dominated_by(c, 0));
  }
  // Half-way along a bone: the tube.
  glm::u8vec4 bone = pixel_at(image, camera, glm::vec3(0.0f, 1.4f, 0.0f));
  INFO("bone: " << describe(bone));
  CHECK(dominated_by(bone, 0));
  CHECK(glGetError() == GL_NO_ERROR);
}

TEST_CASE("away from the skeleton and above the floor, the background is its colour") {
  OsMesaContext gl(kTestSize);
  REQUIRE(gl.ok());
  SceneRenderer renderer;
  Scene scene;
  scene.skeletons = {three_joint_skeleton(kRed)};
  Image image = render_image(renderer, scene, front_camera(), flat_style());
  // Top corners: the floor fades out long before the horizon, the skeleton is in the middle.
  for (glm::ivec2 p : {glm::ivec2(3, 3), glm::ivec2(kTestSize.x - 4, 3), glm::ivec2(kTestSize.x / 2, 2)}) {
    INFO("pixel " << p.x << ", " << p.y << ": " << describe(image.at(p.x, p.y)));
    CHECK(near_color(image.at(p.x, p.y), kFlatBackground));
  }
}

TEST_CASE("the default background is a dark neutral gradient, lighter at the top") {
  OsMesaContext gl(kTestSize);
  REQUIRE(gl.ok());
  SceneRenderer renderer;
  Image image = render_image(renderer, Scene{}, front_camera(), SceneStyle{});
  glm::u8vec4 top = image.at(kTestSize.x / 2, 1);
  INFO("top " << describe(top));
  CHECK(brightness(top) < 3 * 80);  // dark
  CHECK(std::abs(int(top.r) - int(top.b)) < 12);  // neutral
  // Above the floor (which fades out well below the horizon), lighter towards the top.
  CHECK(brightness(top) >= brightness(image.at(kTestSize.x / 2, kTestSize.y / 4)) - 1);
}

TEST_CASE("two skeletons, two colours, each in its own place") {
  OsMesaContext gl(kTestSize);
  REQUIRE(gl.ok());
  SceneRenderer renderer;
  Scene scene;
  scene.skeletons = {three_joint_skeleton(kRed, -1.0f), three_joint_skeleton(kBlue, 1.0f)};
  OrbitCamera camera = front_camera();
  Image image = render_image(renderer, scene, camera, flat_style());

  for (int i = 0; i < 3; ++i) {
    glm::u8vec4 left = pixel_at(image, camera, scene.skeletons[0].positions[static_cast<size_t>(i)]);
    glm::u8vec4 right = pixel_at(image, camera, scene.skeletons[1].positions[static_cast<size_t>(i)]);
    INFO("joint " << i << ": left " << describe(left) << ", right " << describe(right));
    CHECK(dominated_by(left, 0));
    CHECK(dominated_by(right, 2));
  }
  // Red is left of blue on screen: +X is to the right in a front view.
  CHECK(pixel_of(camera, scene.skeletons[0].positions[1], kTestSize).x <
        pixel_of(camera, scene.skeletons[1].positions[1], kTestSize).x);
  // Between them, above their heads: background.
  CHECK(near_color(pixel_at(image, camera, glm::vec3(0.0f, 2.3f, 0.0f)), kFlatBackground));
}

TEST_CASE("a highlighted joint takes the highlight colour, the others keep theirs") {
  OsMesaContext gl(kTestSize);
  REQUIRE(gl.ok());
  SceneRenderer renderer;
  Scene scene;
  SkeletonPose pose = three_joint_skeleton(kRed);
  pose.highlights.assign(3, glm::vec4(0.0f));
  pose.highlights[2] = glm::vec4(0.1f, 0.95f, 0.2f, 1.0f);
  scene.skeletons = {pose};
  OrbitCamera camera = front_camera();
  Image image = render_image(renderer, scene, camera, flat_style());
  glm::u8vec4 lit = pixel_at(image, camera, pose.positions[2]);
  glm::u8vec4 plain = pixel_at(image, camera, pose.positions[0]);
  INFO("highlighted " << describe(lit) << ", plain " << describe(plain));
  CHECK(dominated_by(lit, 1));
  CHECK(dominated_by(plain, 0));
}

TEST_CASE("the same skeleton in centimetres, framed by its size, looks the same") {
  OsMesaContext gl(kTestSize);
  REQUIRE(gl.ok());
  SceneRenderer renderer;
  const float aspect = static_cast<float>(kTestSize.x) / static_cast<float>(kTestSize.y);
  Image images[2];
  OrbitCamera cameras[2];
  for (int i = 0; i < 2; ++i) {
    float unit = i == 0 ? 1.0f : 100.0f;
    Scene scene;
    SkeletonPose pose = three_joint_skeleton(kRed);
    for (glm::vec3& p : pose.positions) p *= unit;
    pose.size *= unit;
    scene.skeletons = {pose};
    cameras[i].yaw = 0.5f;
    cameras[i].pitch = 0.2f;
    cameras[i].frame(pose_bounds(pose), aspect);
    images[i] = render_image(renderer, scene, cameras[i], flat_style());
  }
  int differing = 0;
  for (size_t i = 0; i < images[0].rgba.size(); ++i)
    differing += std::abs(int(images[0].rgba[i]) - int(images[1].rgba[i])) > 8 ? 1 : 0;
  // Same picture up to a few edge pixels and the grid (whose spacing is a power of ten).
  CHECK(differing < static_cast<int>(images[0].rgba.size() / 50));
  CHECK(dominated_by(pixel_at(images[1], cameras[1], glm::vec3(0.0f, 100.0f, 0.0f)), 0));
}
