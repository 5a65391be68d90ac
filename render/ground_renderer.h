#pragma once
// Everything behind the skeletons: the backdrop gradient; the floor, a disc around the
// camera's target with an anti-aliased grid that fades into the backdrop, and soft contact
// shadows; a ring in the skeleton's colour under every joint flagged as touching the ground.
//
// Shadows are blobs (one per joint and two per bone, darker and tighter the closer to the
// ground) drawn with max-blending into a 256^2 texture that covers the skeletons from above,
// then laid on the floor over that rectangle only. Max, not sum: overlapping blobs never
// darken past one blob.
//
// Cost at 1280x720 on llvmpipe: each pixel is shaded once, by the floor or by the backdrop
// (depth-tested behind it), plus the shadow rectangle and a few quads.
#include <vector>

#include <glm/glm.hpp>

#include "render/camera.h"
#include "render/instanced_mesh.h"
#include "render/shader.h"
#include "render/skeleton_pose.h"

namespace mostyle::render {

struct GroundStyle {
  glm::vec3 background_top{0.155f, 0.160f, 0.172f};  // sRGB, dark neutral
  glm::vec3 background_bottom{0.090f, 0.093f, 0.100f};
  float vignette = 0.25f;  // darkening at the corners, 0: none
  bool floor = true;
  bool grid = true;
  bool shadows = true;
  bool contacts = true;
  // Minor grid spacing in world units; 0 picks a power of ten from the skeletons' size
  // (10 for ~170 cm skeletons, 1 for CMU's ~30 units). Major lines every 10 minor.
  float grid_spacing = 0.0f;
  glm::vec3 color{0.205f, 0.212f, 0.228f};  // the floor, sRGB
  glm::vec3 minor_line_color{0.255f, 0.262f, 0.280f};
  glm::vec3 major_line_color{0.330f, 0.338f, 0.360f};
  glm::vec3 x_axis_color{0.55f, 0.28f, 0.28f};
  glm::vec3 z_axis_color{0.28f, 0.36f, 0.58f};
  float shadow_strength = 0.7f;  // darkening of the floor under a joint resting on it
};

// Minor grid spacing for skeletons of `size` world units: 10^floor(log10(size / 4)).
float auto_grid_spacing(float size);

class GroundRenderer {
 public:
  // Needs a current GL 3.3 core context. Throws std::runtime_error when a shader fails.
  GroundRenderer();
  ~GroundRenderer();
  GroundRenderer(const GroundRenderer&) = delete;
  GroundRenderer& operator=(const GroundRenderer&) = delete;

  // Paints every pixel of the viewport `size` of the bound framebuffer (colour; depth is
  // cleared, then the floor's). Renders the shadow texture first and restores the framebuffer
  // binding and viewport. Leaves depth testing on (GL_LESS), blending off.
  void draw(const std::vector<SkeletonPose>& poses, float ground_height, const OrbitCamera& camera,
            const glm::ivec2& size, const GroundStyle& style = {});

 private:
  // Renders the blobs; *rect = (x, z origin, 1 / side, 1), or all 0 when there is no shadow.
  void draw_shadow_map(const std::vector<SkeletonPose>& poses, float ground_height, const glm::vec3& focus,
                       glm::vec4* rect);
  // The passes of draw, in order: the floor disc (grid, axes) fading at fade_radius around the
  // camera's target; the background where the floor is not; the shadow texture laid on the floor;
  // the contact markers under planted joints.
  void draw_floor(const glm::mat4& view_projection, const glm::vec2& viewport, float stage, float fade_radius,
                  float ground_height, const OrbitCamera& camera, const GroundStyle& style);
  void draw_background(const glm::vec2& viewport, const GroundStyle& style);
  void draw_shadow(const glm::mat4& view_projection, const glm::vec4& shadow_rect, float fade_radius,
                   float ground_height, const OrbitCamera& camera, const GroundStyle& style);
  void draw_contact_markers(const std::vector<SkeletonPose>& poses, const glm::mat4& view_projection,
                            float ground_height);

  ShaderProgram background_program_;
  ShaderProgram floor_program_;
  ShaderProgram shadow_program_;
  ShaderProgram blob_program_;
  ShaderProgram marker_program_;
  InstancedMesh quad1_;  // one vec4 per instance: shadow blobs, the shadow rectangle
  InstancedMesh quad2_;  // two vec4 per instance: contact markers
  InstancedMesh disc_;   // one vec4 per instance: the floor
  GLuint empty_vao_ = 0;  // the background triangle has no vertex data, core GL wants a VAO
  GLuint shadow_texture_ = 0;
  GLuint shadow_framebuffer_ = 0;
  std::vector<glm::vec4> instances_;
};

}  // namespace mostyle::render
