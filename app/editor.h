#pragma once
// The editor, independent of where it is shown: one frame() builds the ImGui frame (panels,
// labels, camera input) and renders the viewport, for the GLFW window and for OSMesa alike,
// so an offscreen screenshot shows exactly what the window shows.
//
// The platform (app/window_platform.cpp, app/offscreen_platform.cpp) creates the GL context
// and the ImGui context, feeds ImGui its display size and input, then calls frame() in a loop.
//
// To add a panel: write a ui::Panel in ui/, then add_panel() it in Editor::Editor() (or from
// the platform). Panels see and change the EditorState; the viewport follows it every frame.
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "app/editor_options.h"
#include "render/camera.h"
#include "render/gpu_timer.h"
#include "render/render_target.h"
#include "render/scene_renderer.h"
#include "ui/blend_session.h"
#include "ui/editor_state.h"
#include "ui/panel.h"

namespace mostyle::app {

struct FrameInput {
  glm::ivec2 framebuffer_size{0};  // pixels of the default framebuffer to draw into
  float delta_s = 1.0f / 60.0f;    // time since the previous frame
};

class Editor {
 public:
  // Asks the engine's worker for the pair named in `options` (the bundled pair when none; A
  // with itself for one file) and returns at once: the takes (A, B on A's timeline, the blend)
  // appear when it is ready. A file that fails to load shows its error sentence in the UI and
  // what was loaded before stays; nothing here throws for bad input. Needs no GL context.
  explicit Editor(const EditorOptions& options);
  ~Editor();
  Editor(const Editor&) = delete;
  Editor& operator=(const Editor&) = delete;

  // With the GL context current and the ImGui context created: makes the renderers and
  // initialises ImGui's OpenGL3 back-end. Throws std::runtime_error when GL is unusable.
  void init_graphics();
  // Before the GL context goes away.
  void shutdown_graphics();

  // One frame: ImGui::NewFrame, panels, camera input, ImGui::Render, viewport, ImGui draw
  // data. Draws into framebuffer 0 at input.framebuffer_size. The platform has already set
  // ImGui's display size and input (its own NewFrame).
  void frame(const FrameInput& input);

  // Screenshots: playback starts paused where --frame put it, and no timing text is shown,
  // so two runs (window or offscreen) give the same picture.
  void set_deterministic(bool on) {
    deterministic_ = on;
    if (on) state_.playback.playing = false;
  }

  void add_panel(std::unique_ptr<ui::Panel> panel) { panels_.push_back(std::move(panel)); }
  ui::EditorState& state() { return state_; }
  ui::BlendSession& session() { return *session_; }

  // Takes up the worker's latest results and re-blends if asked (what frame() does first);
  // needs no GL context. Never blocks.
  void update_engine();
  // Blocks until the worker has loaded, decomposed and blended (screenshots, tests), then
  // update_engine().
  void wait_for_engine();
  // Files dropped on the window (the platform's drop callback): loaded as the pair (two) or
  // as B (one) by the files panel on the next frame.
  void drop_files(const std::vector<std::string>& paths);
  const render::OrbitCamera& camera() const { return camera_; }
  // Whether the next frame differs from this one without any input: playing, or the engine
  // (a load, a decomposition, the error sweep) still working. When not, the window platform
  // waits for events instead of drawing (an editor at rest uses next to no CPU).
  bool animating() const;

 private:
  void build_scene();
  void frame_camera(float aspect);

  ui::EditorState state_;
  std::unique_ptr<ui::BlendSession> session_;  // before panels_: they hold references to it
  std::vector<std::unique_ptr<ui::Panel>> panels_;
  const void* framed_pair_ = nullptr;  // the prepared pair the camera was framed on
  int initial_frame_ = 0;              // --frame, applied when the first pair arrives
  bool initial_frame_applied_ = false;
  render::OrbitCamera camera_;
  render::Scene scene_;
  render::SceneStyle style_;
  std::unique_ptr<render::SceneRenderer> scene_renderer_;
  std::unique_ptr<render::RenderTarget> render_target_;
  std::unique_ptr<render::GpuTimer> viewport_timer_;  // the viewport's cost, shown in a corner
  bool graphics_ready_ = false;
  bool camera_framed_ = false;
  bool deterministic_ = false;
  bool software_renderer_ = false;  // llvmpipe & co: no multisampling unless asked
};

}  // namespace mostyle::app
