#pragma once
// The studio lighting every lit surface shares: a warm key light and a cool fill fixed to the
// camera (so a turned skeleton is never in the dark), hemisphere ambient from the world's up
// axis, a rim for silhouettes. Colours are linear; shaders convert to sRGB at the end.
#include <glm/glm.hpp>

#include "render/shader.h"

namespace mostyle::render {

struct Lighting {
  glm::vec3 key_direction{-0.45f, 0.75f, 0.50f};  // towards the light, camera space (x right, y up, z back)
  glm::vec3 key_color{0.95f, 0.90f, 0.82f};
  glm::vec3 fill_direction{0.70f, 0.15f, 0.40f};
  glm::vec3 fill_color{0.22f, 0.26f, 0.34f};
  glm::vec3 sky_ambient{0.30f, 0.32f, 0.36f};
  glm::vec3 ground_ambient{0.10f, 0.09f, 0.08f};
  glm::vec3 rim_color{0.35f, 0.38f, 0.45f};
};

// GLSL 330 source of `vec3 shade(vec3 base_linear, vec3 normal_vs, vec3 position_vs)` and
// `vec3 to_srgb(vec3)`, with the uniforms set_lighting() fills. Pasted into fragment shaders.
extern const char* const kLightingGlsl;

// Sets the kLightingGlsl uniforms on `program` (in use) for this view matrix.
void set_lighting(const ShaderProgram& program, const Lighting& lighting, const glm::mat4& view);

// sRGB colour -> linear, as the shaders expect per-instance colours.
glm::vec3 srgb_to_linear(const glm::vec3& srgb);

}  // namespace mostyle::render
