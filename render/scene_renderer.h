#pragma once
// Everything in the 3D viewport, in one call: backdrop, floor (grid, contact shadows, contact
// markers) and lit skeletons. The app hands it the scene and the camera each frame; it draws
// into whatever framebuffer is bound (the window, an MSAA RenderTarget, OSMesa).
#include <vector>

#include <glm/glm.hpp>

#include "render/camera.h"
#include "render/ground_renderer.h"
#include "render/lighting.h"
#include "render/skeleton_pose.h"
#include "render/skeleton_renderer.h"

namespace mostyle::render {

struct Scene {
  std::vector<SkeletonPose> skeletons;
  float ground_height = 0.0f;  // y of the floor, world units
};

struct SceneStyle {
  GroundStyle ground;  // backdrop and floor
  SkeletonStyle skeleton;
  Lighting lighting;
};

class SceneRenderer {
 public:
  // Needs a current GL 3.3 core context (and for destruction). Throws std::runtime_error when
  // a shader fails to compile.
  SceneRenderer() = default;

  // Draws the scene over the (0, 0, size) rectangle of the bound framebuffer: sets the
  // viewport and paints every pixel, colour and depth (no clear needed). Leaves depth testing
  // on, blending off. O(joints) on the CPU; on the GPU one full-screen pass and ~4k triangles.
  void draw(const Scene& scene, const OrbitCamera& camera, const glm::ivec2& size,
            const SceneStyle& style = {});

 private:
  GroundRenderer ground_;
  SkeletonRenderer skeletons_;
};

}  // namespace mostyle::render
