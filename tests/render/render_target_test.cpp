#include "render/render_target.h"

#include <catch2/catch.hpp>

#include "render/scene_renderer.h"
#include "tests/render/osmesa_context.h"
#include "tests/render/pixel_checks.h"
#include "tests/render/scene_fixtures.h"

using namespace mostyle::render;
using namespace mostyle::test;

TEST_CASE("a multisampled target resolves into the default framebuffer") {
  OsMesaContext gl(kTestSize);
  REQUIRE(gl.ok());
  RenderTarget target;
  REQUIRE(target.resize(kTestSize, 4));
  CHECK(target.size() == kTestSize);
  CHECK(target.samples() >= 1);
  CHECK(target.samples() <= 4);
  GLuint first = target.framebuffer();
  CHECK(target.resize(kTestSize, 4));  // unchanged: nothing reallocated
  CHECK(target.framebuffer() == first);

  SceneRenderer renderer;
  Scene scene;
  scene.skeletons = {three_joint_skeleton(kRed)};
  OrbitCamera camera = front_camera();
  target.bind();
  renderer.draw(scene, camera, kTestSize, flat_style());
  // Paint the default framebuffer white first: every pixel must come from the resolve.
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glClearColor(1, 1, 1, 1);
  glClear(GL_COLOR_BUFFER_BIT);
  target.resolve_to(0, kTestSize);
  Image image = read_framebuffer(kTestSize);
  CHECK(dominated_by(pixel_at(image, camera, scene.skeletons[0].positions[1]), 0));
  CHECK(near_color(image.at(2, 2), kFlatBackground));
  CHECK(glGetError() == GL_NO_ERROR);
}

TEST_CASE("a render target refuses an empty size") {
  OsMesaContext gl(kTestSize);
  REQUIRE(gl.ok());
  RenderTarget target;
  CHECK_FALSE(target.resize(glm::ivec2(0, 10), 4));
  CHECK(target.framebuffer() == 0);
}
