#pragma once
// The editor, independent of where it is shown: one frame() builds the ImGui frame (panels,
// labels, camera input) and renders the viewport, for the GLFW window and for OSMesa alike,
// so an offscreen screenshot shows exactly what the window shows.
//
// The platform (app/editor/window_platform.cpp, app/editor/offscreen_platform.cpp) creates the
// GL context and the ImGui context, feeds ImGui its display size and input, then calls frame()
// in a loop.
//
// To add a panel: write a ui::Panel in ui/, give it a PanelId and a rectangle in ui/panels/layout.h
// (clear of the centre: tests/ui/panels/layout_test.cpp), then add_panel() it in Editor::Editor() (or
// from the platform). Panels see and change the EditorState; the viewport follows it every frame.
#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "app/editor/editor_options.h"
#include "render/camera.h"
#include "render/gpu_timer.h"
#include "render/render_target.h"
#include "render/scene_renderer.h"
#include "ui/model/engine_link.h"
#include "ui/model/unsaved_question.h"
#include "ui/model/edit_history.h"
#include "ui/model/live_source.h"
#include "ui/model/editor_state.h"
#include "ui/model/recent_files.h"
#include "ui/model/session_file.h"
#include "ui/panels/panel.h"
#include "ui/panels/session_dialog.h"

namespace mostyle::ui {
class FilesPanel;
}  // namespace mostyle::ui

namespace mostyle::app {

// Keys the editor reads beyond the few that ImGui 1.86 names (io.KeyMap), as indices into
// io.KeysDown: GLFW's key codes, which the window platform feeds (window_platform.cpp checks
// them at compile time; ASCII for letters and digits). The offscreen platform feeds no keys.
constexpr int kKeyboardF = 'F';           // GLFW_KEY_F
constexpr int kKeyboardZero = '0';        // GLFW_KEY_0
constexpr int kKeyboardF1 = 290;          // GLFW_KEY_F1
constexpr int kKeyboardKeypadZero = 320;  // GLFW_KEY_KP_0
constexpr int kKeyboardE = 'E';           // GLFW_KEY_E
constexpr int kKeyboardZ = 'Z';           // GLFW_KEY_Z: Ctrl+Z undo, Ctrl+Shift+Z redo
constexpr int kKeyboardY = 'Y';           // GLFW_KEY_Y: Ctrl+Y redo
constexpr int kKeyboardS = 'S';           // GLFW_KEY_S: Ctrl+S save the session, Ctrl+Shift+S save as
constexpr int kKeyboardO = 'O';           // GLFW_KEY_O: Ctrl+O open a session

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

  // One frame: ImGui::NewFrame, keys, panels, the shortcuts window, camera input, ImGui::Render,
  // viewport, ImGui draw data. Draws into framebuffer 0 at input.framebuffer_size. The platform
  // has already set ImGui's display size and input (its own NewFrame). The panels are laid out
  // again (ui/panels/layout.h) on the first frame, whenever the display size changes, and on Reset
  // layout. Keys (editor_shortcuts()) count only when ImGui does not want the keyboard.
  void frame(const FrameInput& input);

  // Screenshots: playback starts paused where --frame put it, and no timing text is shown,
  // so two runs (window or offscreen) give the same picture.
  void set_deterministic(bool on) {
    deterministic_ = on;
    if (on) state_.playback.playing = false;
  }

  void add_panel(std::unique_ptr<ui::Panel> panel) { panels_.push_back(std::move(panel)); }
  ui::EditorState& state() { return state_; }
  ui::EngineLink& engine() { return *engine_; }

  // The Live source (the Files panel's Live section; --live): a stream styled with the loaded
  // takes as it arrives, over TCP. While it streams (and after its source closed, until
  // Disconnect) EditorState::takes are its two, the stream and the styled stream, played at the
  // newest frame; ResultView's takes are kept aside meanwhile and come back on Disconnect.
  ui::LiveSource& live() { return live_; }
  bool live_shown() const { return live_shown_; }
  // Connects the live source to its settings' address with the loaded takes and the document's
  // strengths; false when no takes are loaded (connecting, or failing, goes on on its own thread).
  bool connect_live();
  // Blocks until the live source has styled `seconds` of its stream, or ended, or `timeout`
  // passed (screenshots with --live, tests); then update_engine().
  void wait_for_live(double seconds, std::chrono::milliseconds timeout);

  // Takes up the worker's latest results and re-blends if asked (what frame() does first);
  // needs no GL context. Never blocks.
  void update_engine();
  // Blocks until the worker has loaded, decomposed and blended (screenshots, tests), then
  // update_engine().
  void wait_for_engine();
  // Files dropped on the window (the platform's drop callback): loaded as the pair (two) or
  // as B (one) by the files panel on the next frame.
  void drop_files(const std::vector<std::string>& paths);
  // A thread-safe wake-up for an event loop that waits for input at rest (glfwPostEmptyEvent):
  // called on the engine's threads when a job finishes, so its result is drawn at once.
  void set_wake(std::function<void()> wake) { engine_->set_wake(std::move(wake)); }
  const render::OrbitCamera& camera() const { return camera_; }
  // Whether the next frame differs from this one without any input: playing, the engine (a
  // load, a decomposition, the error sweep, an export) still working, or a result of it not yet
  // taken up. When not, the window platform
  // waits for events instead of drawing (an editor at rest uses next to no CPU).
  bool animating() const;
  // Whether the last frame left ImGui laying out (a window appearing or resizing, a popup opened
  // or closed, a dialog asked for): the next frames must be drawn though nothing else changed.
  bool settling() const { return settling_; }

  // Undo and redo (Ctrl+Z; Ctrl+Shift+Z or Ctrl+Y) of every parameter, weight, mode, option and
  // load (ui/model/edit_history.h: a slider drag is one step). false: nothing to undo (redo). A load
  // undone or redone arrives from the worker later, as any load does.
  bool undo();
  bool redo();
  const ui::EditHistory& edits() const { return edits_; }

  // Sessions (.mostyle, ui/model/session_file.h). save_session writes the takes, every parameter, the
  // camera and the playback to `path` (atomically; ".mostyle" added to a name without an
  // extension) and makes it the file Ctrl+S saves to. open_session reads one and applies it: its
  // takes load on the worker, and the playback and the camera are restored once they are in.
  // Both return false with session_message() saying why, one line, and then change nothing (a
  // malformed file: "FILE:LINE: ..."). An opened session is a new document: the undo history
  // starts again with it. A session whose take is missing opens (true) with its other takes
  // (ui::keep_takes; none there: the takes loaded before stay), session_message() naming the
  // file, and no file to save to (Ctrl+S asks where: its file is never written without the take).
  // open_session opens at once; request_open (Ctrl+O's dialog) asks first over unsaved edits.
  bool save_session(const std::string& path);
  bool open_session(const std::string& path);
  const std::string& session_path() const { return session_path_; }  // absolute; "" before a save or open
  // --save-session (EditorOptions::save_session_path): saved once the takes are in, the engine is
  // idle and two frames are drawn. pending until then; the error sentence when it failed.
  bool scripted_save_pending() const { return !scripted_save_path_.empty(); }
  const std::string& scripted_save_error() const { return scripted_save_error_; }
  const std::string& session_message() const { return session_message_.text(); }
  bool session_message_is_error() const { return session_message_.is_error(); }
  // Closing (the window's close button) or opening a session (request_open): with unsaved edits
  // (ui::EditHistory::unsaved) the editor asks first, a modal with Save (to the session's file, or
  // asking where as Ctrl+S does), Discard and Cancel (ui/model/unsaved_question.h); without, it
  // goes ahead at once. The platform ends its loop once may_close().
  void request_close() { question_.request(edits_.unsaved()); }
  void request_open(const std::string& path);
  // Ctrl+O: the Open session dialog, starting on the session's file, the newest recent session,
  // or the folder sessions go to (session_folder).
  void command_open();
  bool may_close() const { return question_.may_close(); }
  bool asking_unsaved() const { return question_.asking(); }
  // The question's buttons: Save (saving, then going ahead once saved), Discard or Cancel.
  void answer_unsaved(ui::UnsavedQuestion::Answer answer);
  // Where session files and exports given without a folder go, and where their dialogs start:
  // the session's folder, else the first take's (absolute). One rule for every file the editor
  // writes.
  std::string session_folder() const;

  // The takes and sessions opened before (options.recent_path: kept across restarts there).
  const ui::RecentFiles& recent_files() const { return state_.recent; }

 private:
  // The steps of frame() after the keys and the playback, in its order.
  void draw_windows();  // the panels and the editor's own windows, the edits recorded, the scene built
  void center_view();   // the view's centre and framing in the part of the window no panel covers
  void move_camera(float aspect, float delta_s);  // framed, restored, the mouse, following
  void draw_overlays();  // the skeletons' labels, the viewport's timing
  void draw_viewport(const glm::ivec2& size);  // the scene into the window's framebuffer, timed
  void record_frame_times(std::chrono::steady_clock::time_point cpu_start);  // for the metrics panel
  bool imgui_settling();  // settling(), after the frame is drawn
  void build_scene();
  void frame_camera(float aspect);
  void follow_skeletons(float delta_s);  // the camera after the skeletons (view.follow)
  // F, F1 / ?, Esc, Ctrl+0, Ctrl+E, Ctrl+Z / Ctrl+Shift+Z / Ctrl+Y, Ctrl+S / Ctrl+Shift+S, Ctrl+O
  // (space and the arrows: the playback panel)
  void handle_keys();
  void draw_keys_window();  // the list of keys, with Frame all and Reset layout
  // Sessions: Ctrl+S / Ctrl+Shift+S / Ctrl+O, the path dialog they open, the message window.
  void command_save(bool ask);
  void draw_session_windows();  // the dialog (carrying out what it asks) or the message
  void draw_unsaved_question();  // Save / Discard / Cancel, while question_ asks
  void open_when_answered();     // the session request_open asked for, once it may be opened
  void restore_camera(float aspect);  // an opened session's camera, once its takes are in
  void save_session_when_ready();     // --save-session
  void keep_recent_files();           // recent.json follows the session's recent takes
  // The live source: --live connected once the takes are in, the takes and strengths handed on
  // (live_style_spec: new takes or another mode restyle it, the connection kept), its window
  // taken up and shown instead of ResultView's takes (or those back), the playhead at its head.
  void update_live();
  void show_live_takes(bool changed);
  void show_result_takes();
  // Runs `engine_call` (the engine link's poll, sync, wait) on ResultView's takes, also while the
  // live takes are shown.
  template <class F>
  void on_result_takes(F&& engine_call);
  void save_recent_files();

  ui::EditorState state_;
  std::unique_ptr<ui::EngineLink> engine_;  // before panels_: they hold references to it
  ui::LiveSource live_;                        // before panels_ too
  bool live_shown_ = false;                    // state_.shown are the live source's
  bool live_on_start_ = false;                 // --live: connect once the takes are in
  std::vector<ui::ShownMotion> result_takes_;         // ResultView's, aside while the live takes are shown
  std::vector<ui::CycleProvenance> result_provenance_;
  std::vector<std::unique_ptr<ui::Panel>> panels_;
  ui::FilesPanel* files_panel_ = nullptr;  // in panels_; owns the export dialog (animating())
  const void* framed_pair_ = nullptr;  // the prepared pair or palette the camera was framed on
  int initial_frame_ = 0;              // --frame, applied when the first pair arrives
  bool initial_frame_applied_ = false;
  glm::vec2 layout_display_{0.0f};  // the display size the panels were last laid out for
  render::OrbitCamera camera_;
  render::Scene scene_;
  render::SceneStyle style_;
  std::unique_ptr<render::SceneRenderer> scene_renderer_;
  std::unique_ptr<render::RenderTarget> render_target_;
  std::unique_ptr<render::GpuTimer> viewport_timer_;  // the viewport's cost, shown in a corner
  bool graphics_ready_ = false;
  bool camera_framed_ = false;
  double followed_time_s_ = -1.0;  // the playhead when the camera last followed the skeletons
  std::optional<glm::vec3> followed_centre_;  // where the skeletons were then; none: after a reframe
  float free_fraction_ = 1.0f;  // of the window's size that no panel covers (framing)
  bool deterministic_ = false;
  bool settling_ = false;     // settling()
  int popups_open_ = 0;       // ImGui's open popups after the frame before
  bool asked_shown_ = false;  // the unsaved question was asking after the frame before
  bool software_renderer_ = false;  // llvmpipe & co: no multisampling unless asked

  ui::EditHistory edits_;  // undo and redo
  // Sessions. What an opened session restores once its takes are in (the new pair resets the
  // playhead and frames the camera): the playback in update_engine(), the camera in frame().
  struct ViewRestore {
    std::optional<ui::SessionCamera> camera;
    ui::Playback playback;
    bool takes_in = false;
  };
  std::optional<ViewRestore> restore_;
  std::string session_path_;
  std::string scripted_save_path_, scripted_save_error_;  // --save-session
  int frames_drawn_ = 0;
  ui::SessionMessage session_message_;
  ui::SessionDialog dialog_;
  ui::UnsavedQuestion question_;
  std::string session_folder_;  // the last session opened's folder (session_folder)
  // Recent takes and sessions; recent_path_ empty: not kept across restarts (tests, screenshots).
  std::string recent_path_;
  std::vector<std::string> seen_recent_;  // state_.recent.takes as last written
};

}  // namespace mostyle::app
