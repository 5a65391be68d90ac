#include "render/ground_renderer.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace mostyle::render {
namespace {

constexpr int kShadowMapSize = 256;   // shadows are soft: a coarse map is enough
constexpr float kShadowReach = 0.6f;    // blobs fade out at this height, times the size
constexpr float kBlobRadius = 0.06f;    // blob radius at the ground, times the size
constexpr float kMarkerRadius = 0.045f; // contact ring radius, times the size
constexpr float kShadowMaxSide = 8.0f;  // widest shadow map, times the size (3 cm texels at 170 cm)

// The backdrop: a vertical gradient with a faint vignette (keeps the eye on the middle).
// Shared by the background pass and the floor, which fades into it.
const char* const kBackdropGlsl = R"GLSL(
uniform vec2 u_viewport;       // pixels
uniform vec3 u_top;
uniform vec3 u_bottom;
uniform float u_vignette;
vec3 backdrop() {
  vec2 uv = gl_FragCoord.xy / u_viewport;
  vec2 d = uv - 0.5;
  return mix(u_bottom, u_top, smoothstep(0.0, 1.0, uv.y)) * (1.0 - u_vignette * dot(d, d));
}
)GLSL";

// The background: a triangle over the screen at the far plane. Drawn after the floor with
// GL_LEQUAL, so it only shades pixels the floor left empty.
const char* const kBackgroundVertex = R"GLSL(#version 330 core
void main() {
  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  gl_Position = vec4(p * 2.0 - 1.0, 1.0, 1.0);
}
)GLSL";

const char* const kBackgroundFragmentMain = R"GLSL(
out vec4 frag_color;
void main() { frag_color = vec4(backdrop(), 1.0); }
)GLSL";

// The floor: a disc around the camera's target, as wide as the fade. Opaque: it mixes the
// backdrop in itself, so nothing is blended and nothing is shaded twice.
const char* const kFloorVertex = R"GLSL(#version 330 core
layout(location = 0) in vec3 a_position;   // unit disc in xz, in rings
layout(location = 1) in vec4 i_centre_radius;
uniform mat4 u_view_projection;
out vec3 v_world;
out float v_alpha;                         // the fade, per ring: linear in between is smooth enough
void main() {
  v_world = i_centre_radius.xyz + a_position * i_centre_radius.w;
  v_alpha = 1.0 - smoothstep(0.35, 1.0, length(a_position.xz));
  gl_Position = u_view_projection * vec4(v_world, 1.0);
}
)GLSL";

// Every operation here runs for every floor pixel (llvmpipe executes both sides of branches),
// so the grid shares one derivative, the fade comes from the vertices and the shadows are a
// separate pass over their own small rectangle.
const char* const kFloorFragmentMain = R"GLSL(
in vec3 v_world;
in float v_alpha;
uniform float u_spacing;       // minor grid spacing, world units
uniform float u_grid;          // 1: grid, 0: plain
uniform vec3 u_color;
uniform vec3 u_minor_color;
uniform vec3 u_major_color;
uniform vec3 u_x_axis_color;
uniform vec3 u_z_axis_color;
out vec4 frag_color;

// Coverage of lines `width` pixels wide at integer values of coord (d: its screen derivative);
// fades out where lines crowd closer than a few pixels instead of shimmering.
float lines(vec2 coord, vec2 d, float width) {
  vec2 g = abs(fract(coord - 0.5) - 0.5) / d;
  return (1.0 - min(min(g.x, g.y) / width, 1.0)) * (1.0 - smoothstep(0.15, 0.45, max(d.x, d.y)));
}

void main() {
  vec2 xz = v_world.xz;
  vec2 coord = xz / u_spacing;
  vec2 d = max(fwidth(coord), vec2(1e-6));
  vec3 c = u_color;
  c = mix(c, u_minor_color, u_grid * lines(coord, d, 1.0));
  c = mix(c, u_major_color, u_grid * lines(coord * 0.1, d * 0.1, 1.4));
  vec2 axis = 1.0 - min(abs(coord) / d / 1.6, 1.0);        // x: the Z axis (x = 0), y: the X axis
  c = mix(c, u_x_axis_color, u_grid * axis.y);
  c = mix(c, u_z_axis_color, u_grid * axis.x);
  frag_color = vec4(mix(backdrop(), c, v_alpha), 1.0);
}
)GLSL";

std::string with_backdrop(const char* main) {
  return std::string("#version 330 core\n") + kBackdropGlsl + main;
}

const char* const kBlobVertex = R"GLSL(#version 330 core
layout(location = 0) in vec3 a_position;   // unit quad in xz
layout(location = 1) in vec4 i_blob;       // x, z, radius, strength
uniform vec4 u_rect;                       // xz origin, 1 / side
out vec2 v_local;
out float v_strength;
void main() {
  v_local = a_position.xz;
  v_strength = i_blob.w;
  vec2 xz = i_blob.xy + a_position.xz * i_blob.z;
  gl_Position = vec4((xz - u_rect.xy) * u_rect.z * 2.0 - 1.0, 0.0, 1.0);
}
)GLSL";

const char* const kBlobFragment = R"GLSL(#version 330 core
in vec2 v_local;
in float v_strength;
out vec4 frag_color;
void main() {
  float d2 = dot(v_local, v_local);
  float falloff = max(1.0 - d2, 0.0);
  frag_color = vec4(v_strength * falloff * falloff, 0.0, 0.0, 1.0);
}
)GLSL";

// The contact shadows on the floor: the shadow map's rectangle, multiplying what is there
// (blend ZERO, ONE_MINUS_SRC_COLOR) by 1 - strength * shadow * the floor's fade.
const char* const kShadowVertex = R"GLSL(#version 330 core
layout(location = 0) in vec3 a_position;   // unit quad in xz
layout(location = 1) in vec4 i_rect;       // xz origin, side, ground height
uniform mat4 u_view_projection;
out vec2 v_uv;
out vec2 v_xz;
void main() {
  v_uv = a_position.xz * 0.5 + 0.5;
  v_xz = i_rect.xy + v_uv * i_rect.z;
  gl_Position = u_view_projection * vec4(v_xz.x, i_rect.w, v_xz.y, 1.0);
}
)GLSL";

const char* const kShadowFragment = R"GLSL(#version 330 core
in vec2 v_uv;
in vec2 v_xz;
uniform sampler2D u_shadow;
uniform float u_strength;
uniform vec2 u_fade_centre;
uniform float u_fade_radius;
out vec4 frag_color;
void main() {
  float fade = 1.0 - smoothstep(0.35, 1.0, length(v_xz - u_fade_centre) / u_fade_radius);
  frag_color = vec4(vec3(u_strength * fade * texture(u_shadow, v_uv).r), 1.0);
}
)GLSL";

const char* const kMarkerVertex = R"GLSL(#version 330 core
layout(location = 0) in vec3 a_position;   // unit quad in xz
layout(location = 1) in vec4 i_centre_radius;
layout(location = 2) in vec4 i_color;
uniform mat4 u_view_projection;
out vec2 v_local;
out vec4 v_color;
void main() {
  v_local = a_position.xz;
  v_color = i_color;
  gl_Position = u_view_projection * vec4(i_centre_radius.xyz + a_position * i_centre_radius.w, 1.0);
}
)GLSL";

// A ring with a faint disc inside: reads as "this foot is planted" without hiding the shadow.
const char* const kMarkerFragment = R"GLSL(#version 330 core
in vec2 v_local;
in vec4 v_color;
out vec4 frag_color;
void main() {
  float d = length(v_local);
  float aa = max(fwidth(d), 1e-4);
  float ring = smoothstep(0.72 - aa, 0.72 + aa, d) * (1.0 - smoothstep(0.97 - aa, 0.97 + aa, d));
  float disc = (1.0 - smoothstep(0.72 - aa, 0.72 + aa, d)) * 0.22;
  frag_color = vec4(v_color.rgb, v_color.a * max(ring, disc));
}
)GLSL";

float stage_size(const std::vector<SkeletonPose>& poses, const OrbitCamera& camera) {
  float size = 0.0f;
  for (const SkeletonPose& pose : poses) size = std::max(size, effective_size(pose));
  return size > 0.0f ? size : std::max(camera.scene_radius(), 1e-6f);
}

}  // namespace

float auto_grid_spacing(float size) {
  if (!(size > 0.0f)) return 1.0f;
  return std::pow(10.0f, std::floor(std::log10(size / 4.0f)));
}

GroundRenderer::GroundRenderer()
    : background_program_("background", kBackgroundVertex, with_backdrop(kBackgroundFragmentMain).c_str()),
      floor_program_("floor", kFloorVertex, with_backdrop(kFloorFragmentMain).c_str()),
      shadow_program_("contact shadows", kShadowVertex, kShadowFragment),
      blob_program_("shadow blobs", kBlobVertex, kBlobFragment),
      marker_program_("contact markers", kMarkerVertex, kMarkerFragment) {
  std::vector<glm::vec3> vertices;
  std::vector<std::uint32_t> indices;
  make_unit_quad(&vertices, &indices);
  quad1_ = InstancedMesh(vertices, indices, 1);
  quad2_ = InstancedMesh(vertices, indices, 2);
  // Rings where the fade changes, so per-vertex alpha follows its smoothstep closely.
  make_unit_disc(96, {0.35f, 0.45f, 0.55f, 0.65f, 0.75f, 0.85f, 0.93f, 1.0f}, &vertices, &indices);
  disc_ = InstancedMesh(vertices, indices, 1);
  glGenVertexArrays(1, &empty_vao_);

  glGenTextures(1, &shadow_texture_);
  glBindTexture(GL_TEXTURE_2D, shadow_texture_);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_R8, kShadowMapSize, kShadowMapSize, 0, GL_RED, GL_UNSIGNED_BYTE, nullptr);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glBindTexture(GL_TEXTURE_2D, 0);

  GLint previous = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previous);
  glGenFramebuffers(1, &shadow_framebuffer_);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, shadow_framebuffer_);
  glFramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, shadow_texture_, 0);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(previous));
}

GroundRenderer::~GroundRenderer() {
  if (empty_vao_ != 0) glDeleteVertexArrays(1, &empty_vao_);
  if (shadow_framebuffer_ != 0) glDeleteFramebuffers(1, &shadow_framebuffer_);
  if (shadow_texture_ != 0) glDeleteTextures(1, &shadow_texture_);
}

void GroundRenderer::draw_shadow_map(const std::vector<SkeletonPose>& poses, float ground_height,
                                     const glm::vec3& focus, glm::vec4* rect) {
  // Blobs: one per joint, two along each bone; size and darkness from the height.
  instances_.clear();
  Bounds area;
  float max_size = 0.0f;
  auto add_blob = [&](const glm::vec3& p, float size) {
    float h = std::max(p.y - ground_height, 0.0f);
    float t = std::min(h / (kShadowReach * size), 1.0f);
    float strength = (1.0f - t) * (1.0f - t);
    if (strength <= 0.0f) return;
    float radius = kBlobRadius * size + 0.35f * h;
    instances_.emplace_back(p.x, p.z, radius, strength);
    area.extend(glm::vec3(p.x - radius, 0.0f, p.z - radius));
    area.extend(glm::vec3(p.x + radius, 0.0f, p.z + radius));
  };
  for (const SkeletonPose& pose : poses) {
    if (!is_valid(pose)) continue;
    float size = effective_size(pose);
    max_size = std::max(max_size, size);
    for (size_t i = 0; i < pose.positions.size(); ++i) {
      if (is_hidden(pose, i)) continue;
      add_blob(pose.positions[i], size);
      int p = pose.parents[i];
      if (p < 0 || is_hidden(pose, static_cast<size_t>(p))) continue;
      for (float t : {0.33f, 0.67f})
        add_blob(glm::mix(pose.positions[static_cast<size_t>(p)], pose.positions[i], t), size);
    }
  }
  if (instances_.empty()) {
    *rect = glm::vec4(0.0f);
    return;
  }
  glm::vec3 extent = area.extent();
  float side = std::max(std::max(extent.x, extent.z), 1e-6f) * 1.02f;
  glm::vec3 centre = area.center();
  // Skeletons far apart would spread the 256 texels thin: keep the map around what is looked at.
  const float max_side = kShadowMaxSide * max_size;
  if (side > max_side) {
    side = max_side;
    centre = focus;
  }
  *rect = glm::vec4(centre.x - 0.5f * side, centre.z - 0.5f * side, 1.0f / side, 1.0f);

  GLint previous_framebuffer = 0;
  GLint previous_viewport[4] = {0, 0, 0, 0};
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previous_framebuffer);
  glGetIntegerv(GL_VIEWPORT, previous_viewport);

  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, shadow_framebuffer_);
  glViewport(0, 0, kShadowMapSize, kShadowMapSize);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_SCISSOR_TEST);
  glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  glEnable(GL_BLEND);
  glBlendEquation(GL_MAX);
  glBlendFunc(GL_ONE, GL_ONE);
  blob_program_.use();
  blob_program_.set("u_rect", glm::vec4(rect->x, rect->y, rect->z, 0.0f));
  quad1_.draw(instances_);
  glBlendEquation(GL_FUNC_ADD);

  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(previous_framebuffer));
  glViewport(previous_viewport[0], previous_viewport[1], previous_viewport[2], previous_viewport[3]);
}

void GroundRenderer::draw_floor(const glm::mat4& view_projection, const glm::vec2& viewport, float stage,
                                float fade_radius, float ground_height, const OrbitCamera& camera,
                                const GroundStyle& style) {
  glDepthFunc(GL_LESS);
  floor_program_.use();
  floor_program_.set("u_view_projection", view_projection);
  floor_program_.set("u_viewport", viewport);
  floor_program_.set("u_top", style.background_top);
  floor_program_.set("u_bottom", style.background_bottom);
  floor_program_.set("u_vignette", style.vignette);
  floor_program_.set("u_spacing", style.grid_spacing > 0.0f ? style.grid_spacing : auto_grid_spacing(stage));
  floor_program_.set("u_grid", style.grid ? 1.0f : 0.0f);
  floor_program_.set("u_color", style.color);
  floor_program_.set("u_minor_color", style.minor_line_color);
  floor_program_.set("u_major_color", style.major_line_color);
  floor_program_.set("u_x_axis_color", style.x_axis_color);
  floor_program_.set("u_z_axis_color", style.z_axis_color);
  instances_.assign(1, glm::vec4(camera.target.x, ground_height, camera.target.z, fade_radius));
  disc_.draw(instances_);
}

void GroundRenderer::draw_background(const glm::vec2& viewport, const GroundStyle& style) {
  // Depth 1.0 passes GL_LEQUAL only where nothing was drawn.
  glDepthFunc(GL_LEQUAL);
  glDepthMask(GL_FALSE);
  background_program_.use();
  background_program_.set("u_viewport", viewport);
  background_program_.set("u_top", style.background_top);
  background_program_.set("u_bottom", style.background_bottom);
  background_program_.set("u_vignette", style.vignette);
  glBindVertexArray(empty_vao_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
}

void GroundRenderer::draw_shadow(const glm::mat4& view_projection, const glm::vec4& shadow_rect, float fade_radius,
                                 float ground_height, const OrbitCamera& camera, const GroundStyle& style) {
  // On the floor, under everything the skeletons will draw: no depth test needed.
  glDisable(GL_DEPTH_TEST);
  glEnable(GL_BLEND);
  glBlendFuncSeparate(GL_ZERO, GL_ONE_MINUS_SRC_COLOR, GL_ZERO, GL_ONE);
  shadow_program_.use();
  shadow_program_.set("u_view_projection", view_projection);
  shadow_program_.set("u_strength", style.shadow_strength);
  shadow_program_.set("u_fade_centre", glm::vec2(camera.target.x, camera.target.z));
  shadow_program_.set("u_fade_radius", fade_radius);
  shadow_program_.set("u_shadow", 0);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, shadow_texture_);
  instances_.assign(1, glm::vec4(shadow_rect.x, shadow_rect.y, 1.0f / shadow_rect.z, ground_height));
  quad1_.draw(instances_);
  glBindTexture(GL_TEXTURE_2D, 0);
  glDisable(GL_BLEND);
  glEnable(GL_DEPTH_TEST);
}

void GroundRenderer::draw_contact_markers(const std::vector<SkeletonPose>& poses, const glm::mat4& view_projection,
                                          float ground_height) {
  instances_.clear();
  for (const SkeletonPose& pose : poses) {
    if (!is_valid(pose) || pose.contacts.empty()) continue;
    float pose_size = effective_size(pose);
    for (size_t i = 0; i < pose.positions.size(); ++i) {
      if (!pose.contacts[i] || is_hidden(pose, i)) continue;
      const glm::vec3& p = pose.positions[i];
      instances_.emplace_back(p.x, ground_height, p.z, kMarkerRadius * pose_size);
      instances_.emplace_back(glm::min(pose.color * 1.15f + 0.05f, glm::vec3(1.0f)), 0.9f);
    }
  }
  if (instances_.empty()) return;
  // On the floor, under everything the skeletons will draw: no depth test needed.
  glDisable(GL_DEPTH_TEST);
  glEnable(GL_BLEND);
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
  marker_program_.use();
  marker_program_.set("u_view_projection", view_projection);
  quad2_.draw(instances_);
  glDisable(GL_BLEND);
  glEnable(GL_DEPTH_TEST);
}

void GroundRenderer::draw(const std::vector<SkeletonPose>& poses, float ground_height,
                          const OrbitCamera& camera, const glm::ivec2& size, const GroundStyle& style) {
  const float stage = stage_size(poses, camera);
  glm::vec4 shadow_rect(0.0f);
  if (style.floor && style.shadows) draw_shadow_map(poses, ground_height, camera.target, &shadow_rect);

  const float aspect = static_cast<float>(size.x) / static_cast<float>(std::max(size.y, 1));
  const glm::mat4 view_projection = camera.view_projection(aspect);
  const float fade_radius = std::max(7.0f * stage, 1.6f * camera.distance);

  glViewport(0, 0, size.x, size.y);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glEnable(GL_DEPTH_TEST);
  glDepthMask(GL_TRUE);
  glClearDepth(1.0);
  glClear(GL_DEPTH_BUFFER_BIT);
  const glm::vec2 viewport(static_cast<float>(size.x), static_cast<float>(size.y));
  if (style.floor) draw_floor(view_projection, viewport, stage, fade_radius, ground_height, camera, style);
  draw_background(viewport, style);
  if (shadow_rect.w > 0.0f) draw_shadow(view_projection, shadow_rect, fade_radius, ground_height, camera, style);
  if (style.floor && style.contacts) draw_contact_markers(poses, view_projection, ground_height);
  glUseProgram(0);
}

}  // namespace mostyle::render
