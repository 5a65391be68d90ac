#include "render/skeleton_renderer.h"

#include <algorithm>
#include <string>

namespace mostyle::render {
namespace {

// Joints are spheres ray-cast on camera-facing quads: two triangles each instead of hundreds,
// exact silhouettes at any zoom. The quad lies in the plane through the centre perpendicular to
// the eye ray, where the sphere's silhouette cone cuts a circle of radius r*d/sqrt(d^2 - r^2);
// it is made a little larger so the anti-aliased edge has room.
const char* const kJointVertex = R"GLSL(#version 330 core
layout(location = 0) in vec3 a_position;        // unit quad in xz: the corner is (x, z)
layout(location = 1) in vec4 i_centre_radius;
layout(location = 2) in vec4 i_color_glow;
uniform mat4 u_view;
uniform mat4 u_projection;
out vec3 v_point;            // camera space, on the quad: the eye ray goes through it
out vec2 v_local;            // quad coordinates, the silhouette is the unit circle
flat out vec4 v_sphere;      // camera-space centre, radius
flat out vec4 v_color;
const float kEdgeRoom = 1.15;
void main() {
  vec3 c = (u_view * vec4(i_centre_radius.xyz, 1.0)).xyz;
  float r = i_centre_radius.w;
  float d = max(length(c), 1e-20);
  vec3 f = c / d;
  vec3 helper = abs(f.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
  vec3 u = normalize(cross(helper, f));
  vec3 w = cross(f, u);
  float silhouette = r * d / sqrt(max(d * d - r * r, 1e-6 * d * d));
  v_local = a_position.xz * kEdgeRoom;
  v_point = c + (u * v_local.x + w * v_local.y) * silhouette;
  v_sphere = vec4(c, r);
  v_color = i_color_glow;
  gl_Position = u_projection * vec4(v_point, 1.0);
}
)GLSL";

const char* const kJointFragmentHead = R"GLSL(#version 330 core
in vec3 v_point;
in vec2 v_local;
flat in vec4 v_sphere;
flat in vec4 v_color;
uniform mat4 u_projection;
uniform int u_multisampled;   // 1: alpha is coverage (alpha-to-coverage smooths the edge)
out vec4 frag_color;
)GLSL";

const char* const kJointFragmentMain = R"GLSL(
void main() {
  float q = length(v_local);
  float coverage = clamp((1.0 - q) / max(fwidth(q), 1e-6) + 0.5, 0.0, 1.0);
  if (coverage <= (u_multisampled != 0 ? 0.0 : 0.5)) discard;
  vec3 dir = normalize(v_point);
  vec3 c = v_sphere.xyz;
  float b = dot(dir, c);
  float h = max(b * b - dot(c, c) + v_sphere.w * v_sphere.w, 0.0);  // 0 on the silhouette fringe
  vec3 p = dir * (b - sqrt(h));
  vec3 n = normalize(p - c);
  vec3 lit = shade(v_color.rgb, n, p) + v_color.rgb * v_color.a;
  frag_color = vec4(to_srgb(lit), coverage);
  vec4 clip = u_projection * vec4(p, 1.0);
  gl_FragDepth = clamp(clip.z / clip.w * 0.5 + 0.5, 0.0, 1.0);
}
)GLSL";

// A tube from a (radius ra) to b (radius rb); its normal leans along the axis by the taper.
const char* const kBoneVertex = R"GLSL(#version 330 core
layout(location = 0) in vec3 a_position;        // x = cos, z = sin, y = 0 at a, 1 at b
layout(location = 1) in vec4 i_a;
layout(location = 2) in vec4 i_b;
layout(location = 3) in vec4 i_color_glow;
uniform mat4 u_view;
uniform mat4 u_projection;
out vec3 v_normal;
out vec3 v_position;
out vec4 v_color;
void main() {
  vec3 axis = i_b.xyz - i_a.xyz;
  float len = max(length(axis), 1e-20);
  vec3 dir = axis / len;
  vec3 helper = abs(dir.y) < 0.95 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
  vec3 u = normalize(cross(helper, dir));
  vec3 w = cross(dir, u);
  vec3 radial = u * a_position.x + w * a_position.z;
  float r = mix(i_a.w, i_b.w, a_position.y);
  vec4 p = u_view * vec4(i_a.xyz + axis * a_position.y + radial * r, 1.0);
  v_position = p.xyz;
  v_normal = mat3(u_view) * normalize(radial + dir * (i_a.w - i_b.w) / len);
  v_color = i_color_glow;
  gl_Position = u_projection * p;
}
)GLSL";

const char* const kSurfaceFragmentHead = R"GLSL(#version 330 core
in vec3 v_normal;
in vec3 v_position;
in vec4 v_color;
out vec4 frag_color;
)GLSL";

const char* const kSurfaceFragmentMain = R"GLSL(
void main() {
  vec3 lit = shade(v_color.rgb, v_normal, v_position);
  lit += v_color.rgb * v_color.a;  // highlight glow
  frag_color = vec4(to_srgb(lit), 1.0);
}
)GLSL";

std::string surface_fragment() {
  return std::string(kSurfaceFragmentHead) + kLightingGlsl + kSurfaceFragmentMain;
}

std::string joint_fragment() { return std::string(kJointFragmentHead) + kLightingGlsl + kJointFragmentMain; }

glm::vec4 shaded_color(const glm::vec3& base, const glm::vec4& highlight, float amount, float glow) {
  float a = std::clamp(highlight.a * amount, 0.0f, 1.0f);
  glm::vec3 srgb = glm::mix(base, glm::vec3(highlight), a);
  return glm::vec4(srgb_to_linear(srgb), a * glow);
}

}  // namespace

SkeletonRenderer::SkeletonRenderer()
    : joint_program_("skeleton joints", kJointVertex, joint_fragment().c_str()),
      bone_program_("skeleton bones", kBoneVertex, surface_fragment().c_str()) {
  std::vector<glm::vec3> vertices;
  std::vector<std::uint32_t> indices;
  make_unit_quad(&vertices, &indices);
  sphere_ = InstancedMesh(vertices, indices, 2);
  make_unit_tube(16, &vertices, &indices);
  tube_ = InstancedMesh(vertices, indices, 3);
}

void SkeletonRenderer::build_instances(const std::vector<SkeletonPose>& poses, const SkeletonStyle& style,
                                       std::vector<glm::vec4>* joints, std::vector<glm::vec4>* bones) {
  joints->clear();
  bones->clear();
  std::vector<float> radius;
  std::vector<int> child_count;
  for (const SkeletonPose& pose : poses) {
    if (!is_valid(pose)) continue;
    const size_t n = pose.positions.size();
    const float size = effective_size(pose);
    const float degenerate = 1e-4f * size;  // bones shorter than this are not drawn

    // A joint's radius shrinks where its bones are short (hands), so spheres do not merge.
    child_count.assign(n, 0);
    std::vector<float> longest(n, 0.0f);
    for (size_t i = 0; i < n; ++i) {
      int p = pose.parents[i];
      if (p < 0 || is_hidden(pose, i) || is_hidden(pose, static_cast<size_t>(p))) continue;
      ++child_count[static_cast<size_t>(p)];
      float len = glm::length(pose.positions[i] - pose.positions[static_cast<size_t>(p)]);
      if (len <= degenerate) continue;
      longest[i] = std::max(longest[i], len);
      longest[static_cast<size_t>(p)] = std::max(longest[static_cast<size_t>(p)], len);
    }
    radius.assign(n, 0.0f);
    for (size_t i = 0; i < n; ++i) {
      float r = style.joint_radius * size;
      if (child_count[i] == 0) r *= style.leaf_joint_scale;
      if (longest[i] > 0.0f) r = std::min(r, 0.35f * longest[i]);
      radius[i] = r;
    }

    const glm::vec4 no_highlight(0.0f);
    for (size_t i = 0; i < n; ++i) {
      if (is_hidden(pose, i)) continue;
      const glm::vec4& h = pose.highlights.empty() ? no_highlight : pose.highlights[i];
      joints->emplace_back(pose.positions[i], radius[i]);
      joints->push_back(shaded_color(pose.color, h, 1.0f, style.highlight_glow));
      int p = pose.parents[i];
      if (p < 0 || is_hidden(pose, static_cast<size_t>(p))) continue;
      const glm::vec3& a = pose.positions[static_cast<size_t>(p)];
      const glm::vec3& b = pose.positions[i];
      if (glm::length(b - a) <= degenerate) continue;
      float parent_r = radius[static_cast<size_t>(p)];
      bones->emplace_back(a, style.bone_radius_start * parent_r);
      bones->emplace_back(b, std::min(style.bone_radius_end * parent_r, radius[i]));
      bones->push_back(shaded_color(pose.color, h, 0.6f, style.highlight_glow));
    }
  }
}

void SkeletonRenderer::draw(const std::vector<SkeletonPose>& poses, const glm::mat4& view,
                            const glm::mat4& projection, const Lighting& lighting,
                            const SkeletonStyle& style) {
  build_instances(poses, style, &joint_instances_, &bone_instances_);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  GLint sample_buffers = 0;
  glGetIntegerv(GL_SAMPLE_BUFFERS, &sample_buffers);
  for (auto* pass : {&joint_program_, &bone_program_}) {
    pass->use();
    pass->set("u_view", view);
    pass->set("u_projection", projection);
    set_lighting(*pass, lighting, view);
    if (pass == &joint_program_) {
      pass->set("u_multisampled", sample_buffers > 0 ? 1 : 0);
      if (sample_buffers > 0) glEnable(GL_SAMPLE_ALPHA_TO_COVERAGE);
      sphere_.draw(joint_instances_);
      glDisable(GL_SAMPLE_ALPHA_TO_COVERAGE);
    } else {
      tube_.draw(bone_instances_);
    }
  }
  glUseProgram(0);
}

}  // namespace mostyle::render
