#include "render/lighting.h"

#include <cmath>

namespace mostyle::render {

const char* const kLightingGlsl = R"GLSL(
uniform vec3 u_key_dir;     // camera space, unit, towards the light
uniform vec3 u_key_color;
uniform vec3 u_fill_dir;
uniform vec3 u_fill_color;
uniform vec3 u_sky;
uniform vec3 u_ground;
uniform vec3 u_rim_color;
uniform vec3 u_up_vs;       // world up in camera space

vec3 shade(vec3 base, vec3 n, vec3 p) {
  n = normalize(n);
  vec3 v = normalize(-p);
  float hemi = dot(n, u_up_vs) * 0.5 + 0.5;
  vec3 ambient = mix(u_ground, u_sky, hemi);
  float key = max(dot(n, u_key_dir), 0.0);
  // Wrapped fill: soft, reaches a little past the terminator.
  float fill = max((dot(n, u_fill_dir) + 0.3) / 1.3, 0.0);
  vec3 h = normalize(u_key_dir + v);
  float spec = pow(max(dot(n, h), 0.0), 40.0) * 0.22 * step(0.0, dot(n, u_key_dir));
  float rim = pow(1.0 - max(dot(n, v), 0.0), 3.0);
  return base * (ambient + key * u_key_color + fill * u_fill_color) + spec * u_key_color +
         rim * u_rim_color * 0.6;
}

vec3 to_srgb(vec3 c) { return pow(clamp(c, 0.0, 1.0), vec3(1.0 / 2.2)); }
)GLSL";

void set_lighting(const ShaderProgram& program, const Lighting& l, const glm::mat4& view) {
  program.set("u_key_dir", glm::normalize(l.key_direction));
  program.set("u_key_color", l.key_color);
  program.set("u_fill_dir", glm::normalize(l.fill_direction));
  program.set("u_fill_color", l.fill_color);
  program.set("u_sky", l.sky_ambient);
  program.set("u_ground", l.ground_ambient);
  program.set("u_rim_color", l.rim_color);
  program.set("u_up_vs", glm::normalize(glm::mat3(view) * glm::vec3(0.0f, 1.0f, 0.0f)));
}

glm::vec3 srgb_to_linear(const glm::vec3& c) {
  return glm::vec3(std::pow(c.r, 2.2f), std::pow(c.g, 2.2f), std::pow(c.b, 2.2f));
}

}  // namespace mostyle::render
