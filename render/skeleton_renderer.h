#pragma once
// Lit skeletons: a sphere per joint and a tapered tube per bone, each skeleton in its own
// colour, highlighted joints glowing in theirs. Two instanced draw calls for any number of
// skeletons (3 x 38 joints: 114 spheres, 111 tubes); spheres are ray-cast on quads, so the
// whole lot is ~4k triangles, cheap even for llvmpipe. Thickness follows SkeletonPose::size,
// so centimetres and CMU units look alike.
#include <vector>

#include <glm/glm.hpp>

#include "render/instanced_mesh.h"
#include "render/lighting.h"
#include "render/shader.h"
#include "render/skeleton_pose.h"

namespace mostyle::render {

// Proportions, as fractions of SkeletonPose::size.
struct SkeletonStyle {
  float joint_radius = 0.017f;
  float leaf_joint_scale = 0.7f;  // joints without children (End Sites, finger tips)
  float bone_radius_start = 0.75f;  // times the parent joint's radius
  float bone_radius_end = 0.45f;
  float highlight_glow = 0.55f;     // emissive strength of a full highlight
};

class SkeletonRenderer {
 public:
  // Compiles shaders and builds meshes: needs a current GL 3.3 core context. Throws
  // std::runtime_error when a shader does not compile.
  SkeletonRenderer();

  // Draws `poses` into the bound framebuffer with depth testing (enables GL_DEPTH_TEST, leaves
  // blending off). Invalid poses (is_valid() false) are skipped. O(total joints).
  void draw(const std::vector<SkeletonPose>& poses, const glm::mat4& view, const glm::mat4& projection,
            const Lighting& lighting = {}, const SkeletonStyle& style = {});

  // The instance data draw() uploads, exposed for tests: per joint (centre, radius),
  // (linear rgb, glow); per bone (start, radius), (end, radius), (linear rgb, glow).
  static void build_instances(const std::vector<SkeletonPose>& poses, const SkeletonStyle& style,
                              std::vector<glm::vec4>* joints, std::vector<glm::vec4>* bones);

 private:
  ShaderProgram joint_program_;
  ShaderProgram bone_program_;
  InstancedMesh sphere_;  // a quad: spheres are ray-cast
  InstancedMesh tube_;
  std::vector<glm::vec4> joint_instances_, bone_instances_;  // reused between frames
};

}  // namespace mostyle::render
