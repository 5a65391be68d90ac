#pragma once
// An orbit camera for the viewport: it looks at a target point from a distance, turned by
// yaw (about +Y, the up axis of all our data) and pitch. Pure math, no GL: the view and
// projection matrices feed the renderers, and project_to_pixels() gives where a world point
// lands, for labels, picking and tests. Units are whatever the data uses: frame() sets the
// distance and the zoom limits from the size of what is shown, never from a unit guess.
#include <glm/glm.hpp>

#include "render/bounds.h"

namespace mostyle::render {

struct ScreenPoint {
  glm::vec2 pixel{0.0f};  // x right, y down, from the top-left corner; pixel centres at +0.5
  float depth = 0.0f;     // window depth in [0, 1] when visible
  bool visible = false;   // in front of the camera and inside the view volume
};

// World point -> pixel in a viewport of `viewport` pixels, through view_projection.
ScreenPoint project_to_pixels(const glm::mat4& view_projection, const glm::vec3& world,
                              const glm::ivec2& viewport);

class OrbitCamera {
 public:
  // Where the camera looks and from where. yaw 0 looks from +Z towards -Z (a front view of a
  // character facing +Z); positive pitch looks down from above. Angles in radians.
  glm::vec3 target{0.0f};
  float yaw = 0.0f;
  float pitch = 0.0f;
  float distance = 10.0f;    // world units, > 0
  float fov_y = 0.61f;       // vertical field of view, radians (35 degrees)
  // Where the view's centre sits in the window, in normalized device coordinates (0, 0: the
  // window's centre): the editor puts it in the middle of the part no panel covers.
  glm::vec2 lens_shift{0.0f};

  glm::vec3 eye() const;
  glm::vec3 forward() const;  // unit, eye -> target
  glm::vec3 right() const;    // unit, screen right
  glm::vec3 up() const;       // unit, screen up
  glm::mat4 view() const;
  // Perspective for width/height `aspect`; near and far follow the distance and the framed
  // size, so depth precision holds for centimetres as well as for CMU's tenth-feet.
  glm::mat4 projection(float aspect) const;
  glm::mat4 view_projection(float aspect) const { return projection(aspect) * view(); }

  // Centres on `b` and sets the distance at which its corners fill at most `fill` of the
  // view's width and height (for this aspect, yaw and pitch). Sets the zoom limits and clip
  // planes from its size. No-op on an empty box. O(1).
  void frame(const Bounds& b, float aspect, float fill = 0.8f);

  // Mouse gestures, in pixels of a viewport `viewport_height` pixels high. None of them puts
  // the eye under the floor (the plane y = 0, where the editor stands the feet): pitch stays
  // between a few degrees above the horizon and just short of straight down, and more when the
  // target is below the floor (see keep_above_floor()).
  void orbit(float dx_pixels, float dy_pixels);  // drag right turns the scene right, drag up lowers the eye
  void pan(float dx_pixels, float dy_pixels, float viewport_height);  // the scene follows the cursor
  void zoom(float wheel_steps);  // positive zooms in; each step is ~12%, within the limits
  // Raises the pitch (and, at the steepest pitch, the target) until the eye is at least
  // sin(kMinPitch) x distance above the floor. What the gestures call after moving; frame()
  // does not (its caller chooses the angles). O(1).
  void keep_above_floor();
  static constexpr float kMinPitch = 0.06f;  // radians (3.4 degrees): lowest look at the floor

  // Moves the target smoothly towards `point` in x and z (the height stays: following the
  // vertical bob of a walk is tiring to watch). half_life_s: time to cover half the gap.
  void follow(const glm::vec3& point, float dt_s, float half_life_s = 0.25f);

  float scene_radius() const { return scene_radius_; }

 private:
  float scene_radius_ = 1.0f;  // size of what frame() was given; zoom limits and clip planes
};

}  // namespace mostyle::render
