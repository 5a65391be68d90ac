#include "render/png_io.h"

#include <cstdio>
#include <filesystem>

#include <catch2/catch.hpp>

#include "engine/base/error.h"
#include "render/gl.h"
#include "render/scene_renderer.h"
#include "tests/render/osmesa_context.h"
#include "tests/render/pixel_checks.h"
#include "tests/render/scene_fixtures.h"

using namespace mostyle::render;
using namespace mostyle::test;
namespace fs = std::filesystem;

namespace {
std::string temp_png(const std::string& name) {
  return (fs::temp_directory_path() / ("mostyle_render_test_" + name + ".png")).string();
}
}  // namespace

TEST_CASE("write_png then read_png gives the same pixels and size") {
  Image image;
  image.width = 37;
  image.height = 23;
  image.rgba.resize(37 * 23 * 4);
  for (size_t i = 0; i < image.rgba.size(); ++i) image.rgba[i] = static_cast<std::uint8_t>((i * 7) % 251);
  const std::string path = temp_png("roundtrip");
  write_png(image, path);
  Image back = read_png(path);
  CHECK(back.width == 37);
  CHECK(back.height == 23);
  CHECK(back.rgba == image.rgba);
  CHECK_FALSE(fs::exists(path + ".tmp"));
  fs::remove(path);
}

TEST_CASE("write_png fails cleanly: empty image, missing folder") {
  Image image;
  CHECK_THROWS_AS(write_png(image, temp_png("empty")), mostyle::InputError);
  image.width = image.height = 2;
  image.rgba.assign(16, 255);
  const std::string path = (fs::temp_directory_path() / "mostyle_no_such_dir" / "x.png").string();
  CHECK_THROWS_WITH(write_png(image, path), Catch::Contains("x.png") && Catch::Contains("cannot write"));
  CHECK_FALSE(fs::exists(path));
}

TEST_CASE("read_png names the file it cannot read") {
  CHECK_THROWS_WITH(read_png("/nonexistent/mostyle.png"), Catch::Contains("/nonexistent/mostyle.png"));
}

TEST_CASE("read_framebuffer returns rows top first") {
  OsMesaContext gl(kTestSize);
  REQUIRE(gl.ok());
  glDisable(GL_SCISSOR_TEST);
  glClearColor(0, 0, 1, 1);
  glClear(GL_COLOR_BUFFER_BIT);
  glEnable(GL_SCISSOR_TEST);
  glScissor(0, kTestSize.y / 2, kTestSize.x, kTestSize.y / 2);  // GL's upper half
  glClearColor(1, 0, 0, 1);
  glClear(GL_COLOR_BUFFER_BIT);
  glDisable(GL_SCISSOR_TEST);
  Image image = read_framebuffer(kTestSize);
  CHECK(image.at(5, 0) == glm::u8vec4(255, 0, 0, 255));
  CHECK(image.at(5, kTestSize.y - 1) == glm::u8vec4(0, 0, 255, 255));
}

TEST_CASE("a rendered screenshot is written at the framebuffer's size") {
  const glm::ivec2 size(300, 170);
  OsMesaContext gl(size);
  REQUIRE(gl.ok());
  SceneRenderer renderer;
  Scene scene;
  scene.skeletons = {three_joint_skeleton(kRed)};
  OrbitCamera camera = front_camera();
  Image image = render_image(renderer, scene, camera, flat_style(), size);
  const std::string path = temp_png("screenshot");
  write_png(image, path);
  Image back = read_png(path);
  CHECK(back.width == size.x);
  CHECK(back.height == size.y);
  CHECK(back.rgba == image.rgba);
  CHECK(dominated_by(pixel_at(back, camera, scene.skeletons[0].positions[1]), 0));
  fs::remove(path);
}
