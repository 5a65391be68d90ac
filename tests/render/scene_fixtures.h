#pragma once
// Known poses, cameras and styles for the render tests.
#include "render/camera.h"
#include "render/image.h"
#include "render/scene_renderer.h"
#include "render/skeleton_pose.h"

namespace mostyle::test {

inline const glm::vec3 kRed{0.90f, 0.15f, 0.12f};
inline const glm::vec3 kBlue{0.15f, 0.35f, 0.95f};
inline const glm::vec3 kFlatBackground{0.10f, 0.30f, 0.10f};  // green-ish: unlike any skeleton
inline const glm::ivec2 kTestSize{320, 240};

// Three joints straight up at x = `x`: 0.2, 1.0 and 1.8 units high. Size 2.
inline render::SkeletonPose three_joint_skeleton(const glm::vec3& color, float x = 0.0f) {
  render::SkeletonPose pose;
  pose.label = "three";
  pose.color = color;
  pose.positions = {{x, 0.2f, 0.0f}, {x, 1.0f, 0.0f}, {x, 1.8f, 0.0f}};
  pose.parents = {-1, 0, 1};
  pose.size = 2.0f;
  return pose;
}

// A front view, a little from above, of the space the skeletons above stand in.
inline render::OrbitCamera front_camera() {
  render::OrbitCamera camera;
  camera.target = glm::vec3(0.0f, 1.0f, 0.0f);
  camera.yaw = 0.0f;
  camera.pitch = 0.25f;
  camera.distance = 6.0f;
  return camera;
}

// A flat background and no vignette, so "background" is one known colour.
inline render::SceneStyle flat_style() {
  render::SceneStyle style;
  style.ground.background_top = kFlatBackground;
  style.ground.background_bottom = kFlatBackground;
  style.ground.vignette = 0.0f;
  return style;
}

inline render::Image render_image(render::SceneRenderer& renderer, const render::Scene& scene,
                                  const render::OrbitCamera& camera, const render::SceneStyle& style,
                                  const glm::ivec2& size = kTestSize) {
  renderer.draw(scene, camera, size, style);
  return render::read_framebuffer(size);
}

}  // namespace mostyle::test
