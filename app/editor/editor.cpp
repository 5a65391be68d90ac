#include "app/editor/editor.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <system_error>
#include <thread>

#include <imgui.h>
#include <imgui_internal.h>  // ImGuiContext: windows still laid out, popups opened
#include <imgui_impl_opengl3.h>

#include "app/editor/tcp_frame_source.h"
#include "engine/io/bvh/bvh_read.h"
#include "engine/base/error.h"
#include "render/gl.h"
#include "render/skeleton_pose.h"
#include "ui/model/live_style_spec.h"
#include "ui/panels/playback_panel.h"
#include "ui/panels/components_panel.h"
#include "ui/panels/layers_panel.h"
#include "ui/panels/files_panel.h"
#include "ui/panels/layout.h"
#include "ui/panels/metrics_panel.h"
#include "ui/panels/parameters_panel.h"
#include "ui/panels/takes_panel.h"
#include "ui/panels/viewport_overlay.h"

namespace mostyle::app {
namespace {

// Joints closer than this to the floor (times the skeleton's size) get a contact ring when a
// take carries no contacts of the pipeline's own (engine/measure/foot_contact.h).
constexpr float kContactTolerance = 0.04f;
// How much of the view the skeletons fill when framed: room for the floor and the panels.
constexpr float kFrameFill = 0.62f;
// Viewport multisampling of screenshots, whatever the renderer.
constexpr int kScreenshotSamples = 4;

}  // namespace

namespace {

std::string absolute_path(const std::string& path) {
  std::error_code ec;
  const std::filesystem::path p = std::filesystem::absolute(path, ec);
  return (ec ? std::filesystem::path(path) : p).lexically_normal().string();
}

ui::SessionCamera session_camera(const render::OrbitCamera& c) {
  ui::SessionCamera s;
  s.target = {c.target.x, c.target.y, c.target.z};
  s.yaw = c.yaw;
  s.pitch = c.pitch;
  s.distance = c.distance;
  s.fov_y = c.fov_y;
  return s;
}

void set_camera(render::OrbitCamera& c, const ui::SessionCamera& s) {
  c.target = glm::vec3(s.target[0], s.target[1], s.target[2]);
  c.yaw = s.yaw;
  c.pitch = s.pitch;
  c.distance = s.distance;
  c.fov_y = s.fov_y;
}

}  // namespace

Editor::Editor(const EditorOptions& options)
    : engine_(std::make_unique<ui::EngineLink>(BvhReadOptions{options.max_memory_bytes})),
      live_(make_tcp_frame_source) {
  state_.document.parameters = options.initial.parameters;
  state_.playback.playing = !options.initial.paused;
  initial_frame_ = options.initial.frame;
  scripted_save_path_ = options.save_session_path;
  recent_path_ = options.recent_path;
  state_.recent = ui::read_recent_files(recent_path_);  // missing or broken: empty
  if (!options.live_address.empty()) {  // --live: connected once the takes are in
    live_.settings().address = options.live_address;
    live_.settings().skeleton = options.live_skeleton;
    live_on_start_ = true;
  }
  seen_recent_ = state_.recent.takes;
  // The takes go to the engine's worker: aligned, decomposed and blended off this thread. A
  // session brings its own, with every parameter; one that cannot be read says why (on the first
  // frame) and the editor starts as it would without it.
  std::string first_take;
  if (!options.session_path.empty() && open_session(options.session_path)) {
    first_take = engine_->requested_a().empty() ? session_path_ : engine_->requested_a();
  } else {
    const std::vector<std::string> files = options.files.empty() ? default_motion_files() : options.files;
    // --weights (or a pair's --alpha), one per take: parse_editor_options checked their count.
    ui::set_layer_weights(state_.document, options.initial.weights);
    engine_->load_files(files, ui::WeightsOf::kNewTakes);
    first_take = files.empty() ? std::string() : files[0];
  }
  std::string folder = std::filesystem::path(first_take).parent_path().string();
  if (folder.empty()) folder = ".";
  // The panels, drawn in this order each frame. New panels go here.
  add_panel(std::make_unique<ui::TakesPanel>());
  add_panel(std::make_unique<ui::ParametersPanel>(*engine_));
  auto files_panel = std::make_unique<ui::FilesPanel>(*engine_, folder);
  files_panel_ = files_panel.get();
  files_panel->set_live(&live_);
  add_panel(std::move(files_panel));
  add_panel(std::make_unique<ui::LayersPanel>(*engine_));
  add_panel(std::make_unique<ui::ComponentsPanel>(*engine_));
  auto metrics_panel = std::make_unique<ui::MetricsPanel>(*engine_);
  metrics_panel->set_live(&live_);
  add_panel(std::move(metrics_panel));
  add_panel(std::make_unique<ui::PlaybackPanel>());
}

template <class F>
void Editor::on_result_takes(F&& engine_call) {
  if (!live_shown_) {
    engine_call();
    return;
  }
  std::swap(state_.shown, result_takes_);
  std::swap(state_.cycle_provenance, result_provenance_);
  engine_call();
  std::swap(state_.shown, result_takes_);
  std::swap(state_.cycle_provenance, result_provenance_);
}

void Editor::update_engine() {
  // Before poll(): a load the worker has published by now is in the snapshot poll() takes up.
  const bool loading = ui::load_pending(*engine_);
  on_result_takes([this] {
    engine_->poll(state_);
    engine_->sync(state_, /*item_held=*/true);  // the new snapshot shown; worker requests after the panels
  });
  // The takes, any number alike.
  const void* pair = engine_->snapshot().prepared.get();
  if (pair != nullptr && pair != framed_pair_) {  // new takes: frame them, start at --frame once
    framed_pair_ = pair;
    state_.view.request_reframe = true;
    if (const ui::ShownMotion* reference = state_.reference_take()) {
      const int frame = initial_frame_applied_ ? 0 : std::min(initial_frame_, std::max(reference->frames() - 1, 0));
      state_.playback.time_s = (frame + 0.5) / reference->rate();
      initial_frame_applied_ = true;
    }
  }
  // An opened session's playback, once its takes are in (the new pair has just reset the
  // playhead); its camera follows in frame(), over the skeletons placed.
  if (restore_ && !restore_->takes_in && !loading) {
    state_.playback = restore_->playback;
    if (deterministic_) state_.playback.playing = false;
    restore_->takes_in = true;
  }
  keep_recent_files();
  update_live();
}

void Editor::wait_for_engine() {
  on_result_takes([this] { engine_->wait_idle(state_); });
  update_engine();
}

bool Editor::connect_live() {
  const PreparedTakes* takes = engine_->takes();
  if (takes == nullptr) return false;
  live_.connect(live_.settings(), ui::live_style_spec(*takes, state_.document));
  return true;
}

void Editor::wait_for_live(double seconds, std::chrono::milliseconds timeout) {
  live_.wait_until(
      [this, seconds](const ui::LiveStatus& s) {
        const bool ended = s.state == ui::LiveState::kClosed || s.state == ui::LiveState::kFailed ||
                           (s.state == ui::LiveState::kOff && !live_on_start_);
        return ended || (live_.input() != nullptr && live_.input()->frames() >= seconds * live_.input()->fps());
      },
      timeout);
  update_engine();
}

void Editor::update_live() {
  if (live_on_start_ && engine_->takes() != nullptr && !ui::load_pending(*engine_)) {
    live_on_start_ = false;
    connect_live();
  }
  // The styler follows the takes and the document as the editor shows them: strengths as they
  // move (eased to), a new styler, the connection kept, when the takes or the mode change.
  const PreparedTakes* takes = engine_->takes();
  if (live_.active() && takes != nullptr && takes->size() >= 2) live_.set_style(ui::live_style_spec(*takes, state_.document));
  const bool changed = live_.poll();
  const bool show = live_.has_window() && (live_.active() || live_.status().state == ui::LiveState::kClosed);
  if (show) show_live_takes(changed);
  else show_result_takes();
}

void Editor::show_live_takes(bool changed) {
  if (!live_shown_) {  // ResultView's takes aside until the live ones go
    result_takes_ = std::move(state_.shown);
    result_provenance_ = std::move(state_.cycle_provenance);
    state_.shown.clear();
    state_.cycle_provenance.clear();
    live_shown_ = true;
    state_.view.request_reframe = true;
  }
  if (changed || state_.shown.empty()) live_.move_takes_into(&state_.shown);  // as the takes panel left them shown
}

void Editor::show_result_takes() {
  if (!live_shown_) return;
  state_.shown = std::move(result_takes_);
  state_.cycle_provenance = std::move(result_provenance_);
  result_takes_.clear();
  result_provenance_.clear();
  live_shown_ = false;
  state_.view.request_reframe = true;
}

void Editor::drop_files(const std::vector<std::string>& paths) {
  auto& queue = state_.dropped;
  queue.insert(queue.end(), paths.begin(), paths.end());
}

Editor::~Editor() = default;

void Editor::init_graphics() {
  if (!ImGui_ImplOpenGL3_Init("#version 330 core")) throw std::runtime_error("ImGui OpenGL3 back-end failed to start");
  scene_renderer_ = std::make_unique<render::SceneRenderer>();
  render_target_ = std::make_unique<render::RenderTarget>();
  viewport_timer_ = std::make_unique<render::GpuTimer>();
  // Multisampling costs llvmpipe more than the whole scene; a GPU does not notice it.
  // Screenshots always take 4 samples: same picture from the window and from OSMesa.
  const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const std::string name = renderer ? renderer : "";
  software_renderer_ = name.find("llvmpipe") != std::string::npos || name.find("softpipe") != std::string::npos ||
                       name.find("swrast") != std::string::npos;
  graphics_ready_ = true;
}

void Editor::shutdown_graphics() {
  if (!graphics_ready_) return;
  viewport_timer_.reset();
  render_target_.reset();
  scene_renderer_.reset();
  ImGui_ImplOpenGL3_Shutdown();
  graphics_ready_ = false;
}

void Editor::build_scene() {
  scene_.skeletons.clear();
  scene_.ground_height = 0.0f;
  for (const ui::ShownMotion& t : state_.shown) {
    if (!t.ok() || !t.visible) continue;
    render::SkeletonPose pose;
    pose.label = t.label;
    pose.color = t.color;
    pose.positions = render::positions_at(t.positions, ui::frame_at(t, state_.playback.time_s));
    pose.parents = t.parents;
    pose.size = t.size;
    pose.hidden = t.hidden;
    pose.highlights = t.highlights;
    if (state_.view.contacts) {
      const int frame = ui::frame_at(t, state_.playback.time_s);
      if (t.contacts.rows() == t.frames() && t.contacts.cols() == static_cast<Eigen::Index>(t.parents.size())) {
        pose.contacts.assign(t.parents.size(), 0);  // the engine's foot contacts
        for (size_t j = 0; j < t.parents.size(); ++j) pose.contacts[j] = t.contacts(frame, static_cast<Eigen::Index>(j)) > 0.5;
      } else {
        render::mark_ground_contacts(&pose, 0.0f, kContactTolerance * t.size);
      }
    }
    scene_.skeletons.push_back(std::move(pose));
  }
}

void Editor::frame_camera(float aspect) {
  render::Bounds b;
  for (const render::SkeletonPose& pose : scene_.skeletons) b.extend(render::pose_bounds(pose));
  if (b.empty()) return;
  // A three-quarter view across the lanes the takes stand in side by side, from the front of
  // the reference's overall travel (the lanes are across it, ui/model/lanes.h): whichever way the
  // takes face or wander, they stand apart in the view, not one behind the other.
  const Eigen::Vector3d side = engine_->side();
  const float heading = static_cast<float>(std::atan2(-side.z(), side.x()));  // the travel (x, z) = (-side.z, side.x)
  camera_.yaw = heading + 0.65f;
  camera_.pitch = 0.22f;
  camera_.frame(b, aspect, kFrameFill * free_fraction_);
}

bool Editor::imgui_settling() {
  // A window that appeared or changed size is laid out over the next frames (an auto-sized one
  // is measured hidden first), and a popup opened or closed shows in the next: without them, a
  // dialog opened by a button would stay unseen until the mouse moved.
  const ImGuiContext& g = *ImGui::GetCurrentContext();
  bool settling = g.OpenPopupStack.Size != popups_open_ || dialog_.opening() || question_.asking() != asked_shown_;
  popups_open_ = g.OpenPopupStack.Size;
  asked_shown_ = question_.asking();
  for (const ImGuiWindow* w : g.Windows) {
    if (!w->Active && !w->WasActive) continue;
    // (HiddenFramesCanSkipItems is not asked: a child scrolled out of its parent has it on every frame.)
    settling = settling || w->Appearing || w->AutoFitFramesX > 0 || w->AutoFitFramesY > 0 ||
               w->HiddenFramesCannotSkipItems > 0;
  }
  return settling;
}

bool Editor::animating() const {
  const WorkerStatus status = engine_->status();
  return state_.playback.playing || status.stage != WorkerStage::kIdle || status.pending || engine_->has_news() ||
         engine_->sweeping() || scripted_save_pending() ||
         !state_.dropped.empty() || (files_panel_ != nullptr && files_panel_->export_dialog().busy()) || live_.active();
}

void Editor::handle_keys() {
  const ImGuiIO& io = ImGui::GetIO();
  if (io.WantTextInput || io.WantCaptureKeyboard) return;  // typing in a field, holding a slider
  bool toggle_shortcuts = ImGui::IsKeyPressed(kKeyboardF1, false);
  for (ImWchar c : io.InputQueueCharacters) toggle_shortcuts |= c == '?';  // '?' on any keyboard layout
  if (toggle_shortcuts) ui::command_toggle_shortcuts(state_);
  if (state_.view.show_shortcuts && ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape), false))
    state_.view.show_shortcuts = false;
  const bool modifier = io.KeyCtrl || io.KeyAlt || io.KeySuper;
  if (!modifier && ImGui::IsKeyPressed(kKeyboardF, false)) ui::command_frame_all(state_);
  if (io.KeyCtrl && (ImGui::IsKeyPressed(kKeyboardZero, false) || ImGui::IsKeyPressed(kKeyboardKeypadZero, false)))
    ui::command_reset_layout(state_);
  if (io.KeyCtrl && ImGui::IsKeyPressed(kKeyboardE, false)) ui::command_open_export(state_);
  if (io.KeyCtrl && !io.KeyAlt) {
    const bool z = ImGui::IsKeyPressed(kKeyboardZ, true);  // held down, undo and redo repeat
    if (z && !io.KeyShift) undo();
    if ((z && io.KeyShift) || ImGui::IsKeyPressed(kKeyboardY, true)) redo();
    if (ImGui::IsKeyPressed(kKeyboardS, false)) command_save(/*ask=*/io.KeyShift);
    if (ImGui::IsKeyPressed(kKeyboardO, false)) command_open();
  }
}

void Editor::draw_keys_window() {
  if (!state_.view.show_shortcuts) return;
  // Top centre, over the viewport (it is shown when asked for, and closes with Esc).
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(0.5f * display.x, ui::kLayoutMargin), ImGuiCond_Appearing, ImVec2(0.5f, 0.0f));
  bool open = true;
  const ImGuiWindowFlags flags =
      ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoSavedSettings;
  if (ImGui::Begin("Shortcuts", &open, flags)) {
    if (ImGui::BeginTable("##keys", 2, ImGuiTableFlags_SizingFixedFit | ImGuiTableFlags_RowBg)) {
      for (const ShortcutHelp& k : editor_shortcuts()) {
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(k.shortcut);
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(k.action);
      }
      ImGui::EndTable();
    }
    ImGui::Separator();
    if (ImGui::Button("Frame all (F)")) ui::command_frame_all(state_);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Turn and move the camera so that every skeleton is in view");
    ImGui::SameLine();
    if (ImGui::Button("Reset layout (Ctrl+0)")) ui::command_reset_layout(state_);
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("Put every panel back in its place and size for this window: the sides and the bottom,\n"
                        "leaving the middle to the skeletons");
    ImGui::SameLine();
    if (ImGui::Button("Close (Esc)")) open = false;
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Hide this list; F1 or ? shows it again");
  }
  ImGui::End();
  if (!open) state_.view.show_shortcuts = false;
}

void Editor::frame(const FrameInput& input) {
  if (!graphics_ready_) throw std::logic_error("Editor::frame before init_graphics");
  const glm::ivec2 size = glm::max(input.framebuffer_size, glm::ivec2(1));
  const float aspect = static_cast<float>(size.x) / static_cast<float>(size.y);

  ImGui_ImplOpenGL3_NewFrame();
  ImGui::NewFrame();

  const auto cpu_start = std::chrono::steady_clock::now();
  update_engine();  // the worker's latest pair and decomposition, never waiting for it

  // A new display size (the first frame's too) lays the panels out again; then the keys.
  ui::track_display_size(state_, &layout_display_);
  handle_keys();

  // Playback on A's aligned timeline; with loop off it stops on the last frame.
  if (const ui::ShownMotion* reference = state_.reference_take())
    ui::advance_playback(state_.playback, static_cast<double>(input.delta_s), ui::take_length_s(*reference));
  // A live stream plays at its newest frame while it streams.
  if (live_shown_ && live_.active() && !state_.shown.empty())
    state_.playback.time_s = ui::take_length_s(state_.shown.front());

  draw_windows();
  center_view();
  move_camera(aspect, input.delta_s);
  draw_overlays();
  ImGui::Render();

  draw_viewport(size);
  glViewport(0, 0, size.x, size.y);
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  settling_ = imgui_settling();
  ++frames_drawn_;
  save_session_when_ready();
  record_frame_times(cpu_start);
}

void Editor::draw_windows() {
  // Panels first: an alpha moved in this frame is blended and drawn in this frame.
  state_.files_folder = session_folder();
  for (auto& panel : panels_) panel->draw(state_);
  state_.view.reset_layout = false;  // laid out; a Reset layout from the shortcuts window: next frame
  draw_keys_window();
  draw_session_windows();
  draw_unsaved_question();
  // After the panels: what they changed is an undo step once nothing is held (a drag is one).
  edits_.record(state_, *engine_, ImGui::IsAnyItemActive());
  on_result_takes([this] { engine_->sync(state_, ImGui::IsAnyItemActive()); });
  build_scene();
}

void Editor::center_view() {
  // The view's centre in the middle of the part of the window no panel covers (between the side
  // columns, above the bottom strip), and framing sized to that part.
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  const auto rects = ui::compute_layout(display.x, display.y, ui::playback_bar_height());
  const ui::PanelRect& left = rects[static_cast<size_t>(ui::PanelId::kTakes)];
  const ui::PanelRect& right = rects[static_cast<size_t>(ui::PanelId::kComponents)];
  const ui::PanelRect& strip = rects[static_cast<size_t>(ui::PanelId::kLayers)];
  const float x0 = left.x + left.w, x1 = right.x, y0 = 0.0f, y1 = strip.y;
  if (display.x > 0 && display.y > 0 && x1 > x0 && y1 > y0) {
    camera_.lens_shift = glm::vec2((x0 + x1) / display.x - 1.0f, 1.0f - (y0 + y1) / display.y);
    free_fraction_ = std::clamp(std::min((x1 - x0) / display.x, (y1 - y0) / display.y), 0.3f, 1.0f);
  }
}

void Editor::move_camera(float aspect, float delta_s) {
  // Framed once on the first poses, then the mouse and the follow mode move it.
  if (!camera_framed_ || state_.view.request_reframe) {
    frame_camera(aspect);
    followed_centre_.reset();  // framed on the skeletons where they are now
    camera_framed_ = !scene_.skeletons.empty();
    state_.view.request_reframe = scene_.skeletons.empty() && state_.view.request_reframe;
  }
  restore_camera(aspect);
  ui::apply_camera_input(camera_);
  follow_skeletons(delta_s);
}

void Editor::draw_overlays() {
  if (state_.view.labels) ui::draw_skeleton_labels(scene_.skeletons, camera_);
  if (!deterministic_) {  // timings differ run to run: not in screenshots
    // At rest the window draws only on input, so a frame rate would count the waits between
    // events (and read as lag): the cost of a frame is what tells whether it keeps up.
    char status[96];
    if (animating())
      std::snprintf(status, sizeof status, "viewport %.1f ms   %.0f fps", viewport_timer_->milliseconds(),
                    static_cast<double>(ImGui::GetIO().Framerate));
    else
      std::snprintf(status, sizeof status, "viewport %.1f ms   at rest", viewport_timer_->milliseconds());
    ui::draw_viewport_status(status);
  }
}

void Editor::draw_viewport(const glm::ivec2& size) {
  // The scene into the multisampled target, resolved into the window (or, with one sample,
  // straight into the window).
  style_.ground.grid = state_.view.grid;
  style_.ground.shadows = state_.view.shadows;
  style_.ground.contacts = state_.view.contacts;
  const int samples = deterministic_ ? kScreenshotSamples
                      : state_.view.samples > 0 ? state_.view.samples
                      : software_renderer_      ? 1
                                                : 4;
  viewport_timer_->begin();
  if (samples > 1 && render_target_->resize(size, samples)) {
    render_target_->bind();
    scene_renderer_->draw(scene_, camera_, size, style_);
    render_target_->resolve_to(0, size);
  } else {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    scene_renderer_->draw(scene_, camera_, size, style_);
  }
  viewport_timer_->end();
}

void Editor::record_frame_times(std::chrono::steady_clock::time_point cpu_start) {
  // Shown by the metrics panel on the next frame; not in screenshots (they differ run to run).
  state_.times.frame_ms = deterministic_ ? -1.0f
                                      : std::chrono::duration<float, std::milli>(std::chrono::steady_clock::now() - cpu_start).count();
  state_.times.viewport_ms = deterministic_ ? -1.0f : viewport_timer_->milliseconds();
  if (files_panel_ != nullptr) state_.times.export_ms = files_panel_->export_dialog().status().ms;
}

void Editor::follow_skeletons(float delta_s) {
  // Follow the skeletons while they move: playing, or the playhead stepped or dragged, glides
  // towards them; paused, a change that moves them where they stand (a weight, an undo, another
  // content) moves the view with them at once, keeping where the animator put it relative to
  // them. Otherwise the view stays where it was put, so a restored session's camera is the one
  // drawn.
  const bool played = state_.playback.playing || state_.playback.time_s != followed_time_s_;
  followed_time_s_ = state_.playback.time_s;
  if (scene_.skeletons.empty()) {
    followed_centre_.reset();
    return;
  }
  glm::vec3 centre(0.0f);
  for (const render::SkeletonPose& pose : scene_.skeletons) centre += render::pose_bounds(pose).center();
  centre /= static_cast<float>(scene_.skeletons.size());
  if (state_.view.follow && played) {
    camera_.follow(centre, delta_s);
  } else if (state_.view.follow && followed_centre_) {
    const glm::vec3 moved = centre - *followed_centre_;
    camera_.target += glm::vec3(moved.x, 0.0f, moved.z);  // as follow(): not the height
  }
  followed_centre_ = centre;
}

void Editor::save_session_when_ready() {
  if (scripted_save_path_.empty() || frames_drawn_ < 2) return;
  const WorkerStatus status = engine_->status();
  const bool loaded = engine_->snapshot().prepared != nullptr;
  if (status.stage != WorkerStage::kIdle || status.pending || ui::load_pending(*engine_)) return;
  if (!loaded && engine_->error().empty()) return;
  if (!save_session(scripted_save_path_)) scripted_save_error_ = session_message_.text();
  scripted_save_path_.clear();
}

bool Editor::undo() { return edits_.undo(state_, *engine_); }

bool Editor::redo() { return edits_.redo(state_, *engine_); }

bool Editor::save_session(const std::string& path) {
  namespace fs = std::filesystem;
  if (path.empty() || !fs::path(path).has_filename()) {
    session_message_.set("Save: no file name given for the session.", true);
    return false;
  }
  std::string target = path;
  if (fs::path(target).extension().empty()) target += ui::kSessionExtension;
  if (!ui::is_session_path(target)) {  // never over a take or an export by a slip of the keyboard
    session_message_.set("Save: a session's file name ends in .mostyle, not '" + path + "'.", true);
    return false;
  }
  target = absolute_path(target);
  ui::SessionFile file;
  file.document = ui::capture_document(state_);
  for (std::string& f : file.document.files) f = absolute_path(f);  // written relative to the session
  file.camera = session_camera(camera_);
  file.playback = state_.playback;
  try {
    ui::write_session_file(target, file);
  } catch (const InputError& e) {
    session_message_.set(e.what(), true);
    return false;
  }
  session_path_ = target;
  edits_.mark_saved(ui::capture_document(state_));
  ui::remember(state_.recent.sessions, target, ui::kRecentSessions);
  save_recent_files();
  session_message_.set("Saved the session to " + target, false);
  return true;
}

bool Editor::open_session(const std::string& path) {
  if (path.empty()) {
    session_message_.set("Open: no file name given for the session.", true);
    return false;
  }
  const std::string where = absolute_path(path);  // its takes resolve to absolute paths
  ui::SessionFile file;
  try {
    file = ui::read_session_file(where);
  } catch (const InputError& e) {  // unreadable or malformed: nothing changes
    session_message_.set(e.what(), true);
    return false;
  }
  const std::string missing = ui::apply_session_document(file.document, where, state_, *engine_);
  // An opened session is a new document, as in any animation package: no undo reaches back to
  // the one before, which would show other takes under this session's name (and Save would
  // write them into it). What is saved is the document once its takes are in.
  edits_ = ui::EditHistory();
  restore_ = ViewRestore{file.camera, file.playback, false};
  // A session opened without a missing take is not what its file holds: Ctrl+S asks where
  // rather than writing the file without that take.
  session_path_ = missing.empty() ? where : std::string();
  session_folder_ = std::filesystem::path(where).parent_path().string();
  ui::remember(state_.recent.sessions, where, ui::kRecentSessions);
  save_recent_files();
  session_message_.set(missing.empty() ? "Opened the session " + where : missing, !missing.empty());
  return true;
}

void Editor::request_open(const std::string& path) {
  question_.request(edits_.unsaved(), ui::UnsavedQuestion::Leave::kOpen, path);
  open_when_answered();
}

void Editor::open_when_answered() {
  if (const std::optional<std::string> path = question_.take_open()) open_session(*path);
}

std::string Editor::session_folder() const {
  if (!session_path_.empty()) return std::filesystem::path(session_path_).parent_path().string();
  if (!session_folder_.empty()) return session_folder_;
  const std::string& a = engine_->loaded_path(0);
  if (!a.empty()) return std::filesystem::path(absolute_path(a)).parent_path().string();
  return absolute_path(".");
}

void Editor::command_save(bool ask) {
  if (!ask && !session_path_.empty()) {
    save_session(session_path_);
    return;
  }
  const std::string path =
      !session_path_.empty() ? session_path_ : (std::filesystem::path(session_folder()) / "untitled.mostyle").string();
  dialog_.open(ui::SessionDialog::Kind::kSave, path);
}

void Editor::command_open() {
  // The session's file, else the newest recent session, else the folder new sessions go to, so
  // the field never starts empty.
  const std::string path = !session_path_.empty()           ? session_path_
                           : !state_.recent.sessions.empty() ? state_.recent.sessions.front()
                                                             : session_folder() + "/";
  dialog_.open(ui::SessionDialog::Kind::kOpen, path);
}

void Editor::draw_session_windows() {
  ui::SessionDialog::Request asked = dialog_.draw(state_.recent.sessions);
  const bool save = asked.kind == ui::SessionDialog::Kind::kSave;
  // A name typed alone is in the session's folder (else the first take's), as an export's is; a
  // path on the command line is the shell's, from the working folder.
  if (!asked.path.empty() && std::filesystem::path(asked.path).is_relative())
    asked.path = (std::filesystem::path(session_folder()) / asked.path).string();
  if (asked.kind == ui::SessionDialog::Kind::kOpen && edits_.unsaved()) {
    dialog_.done();  // the unsaved question takes over; the session opens once it is answered
    request_open(asked.path);
  } else if (asked.kind != ui::SessionDialog::Kind::kNone) {
    const bool done = save ? save_session(asked.path) : open_session(asked.path);
    if (save) question_.saved(done);  // a Save asked by closing or by opening another session
    if (done) {
      dialog_.done();
    } else {  // said in the dialog, where the path can be corrected
      dialog_.failed(session_message_.text());
      session_message_.clear();
    }
  }
  if (!dialog_.is_open()) {
    question_.saved(false);  // the dialog closed without a save: the editor stays as it is
    session_message_.draw(/*hide_successes=*/deterministic_);
  }
  open_when_answered();
}

void Editor::answer_unsaved(ui::UnsavedQuestion::Answer answer) {
  question_.answer(answer);
  if (answer == ui::UnsavedQuestion::Answer::kSave) {
    if (!session_path_.empty()) question_.saved(save_session(session_path_));
    else command_save(/*ask=*/true);  // where: the session dialog; goes ahead once it has saved
  }
  open_when_answered();
}

void Editor::draw_unsaved_question() {
  constexpr const char* kTitle = "Unsaved edits";
  if (question_.asking() && !ImGui::IsPopupOpen(kTitle)) ImGui::OpenPopup(kTitle);
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(0.5f * display.x, 0.5f * display.y), ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
  if (!ImGui::BeginPopupModal(kTitle, nullptr, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings))
    return;
  const bool opening = question_.leave() == ui::UnsavedQuestion::Leave::kOpen;
  const char* before = opening ? "opening the other session" : "closing";
  if (session_path_.empty())
    ImGui::Text("The edits are not saved in a session. Save them before %s?", before);
  else
    ImGui::Text("The edits since the session was saved are not in it. Save them before %s?", before);
  if (!session_path_.empty()) ImGui::TextColored(ImVec4(0.6f, 0.62f, 0.66f, 1.0f), "%s", session_path_.c_str());
  if (opening) ImGui::TextColored(ImVec4(0.6f, 0.62f, 0.66f, 1.0f), "to open: %s", question_.path().c_str());
  ImGui::Spacing();
  if (ImGui::Button("Save")) answer_unsaved(ui::UnsavedQuestion::Answer::kSave);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(opening ? "Save the session (Ctrl+S), then open the other" : "Save the session (Ctrl+S), then close");
  ImGui::SameLine();
  if (ImGui::Button("Discard")) answer_unsaved(ui::UnsavedQuestion::Answer::kDiscard);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(opening ? "Open the other session without saving: the edits are lost"
                              : "Close without saving: the edits are lost");
  ImGui::SameLine();
  if (ImGui::Button("Cancel") || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape), false))
    answer_unsaved(ui::UnsavedQuestion::Answer::kCancel);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Keep editing (Esc)");
  if (!question_.asking()) ImGui::CloseCurrentPopup();
  ImGui::EndPopup();
}

void Editor::restore_camera(float aspect) {
  if (!restore_ || !restore_->takes_in) return;
  if (restore_->camera) {
    if (!scene_.skeletons.empty()) frame_camera(aspect);  // the zoom limits and clip planes for what is shown
    set_camera(camera_, *restore_->camera);
    followed_time_s_ = state_.playback.time_s;  // drawn as it was saved, not followed on from it
    followed_centre_.reset();
    camera_framed_ = true;
    state_.view.request_reframe = false;
  }
  restore_.reset();
}

void Editor::keep_recent_files() {
  std::vector<std::string>& takes = state_.recent.takes;
  if (takes == seen_recent_) return;
  std::vector<std::string> absolute;
  for (const std::string& p : takes) {  // absolute: a restart may be in another folder
    const std::string a = absolute_path(p);
    if (std::find(absolute.begin(), absolute.end(), a) == absolute.end()) absolute.push_back(a);
  }
  takes = std::move(absolute);
  seen_recent_ = takes;
  save_recent_files();
}

void Editor::save_recent_files() {
  if (recent_path_.empty()) return;
  try {
    ui::write_recent_files(recent_path_, state_.recent);
  } catch (const InputError& e) {  // a read-only home: the list lives for this run only
    std::fprintf(stderr, "mostyle: %s (recent files are not kept)\n", e.what());
    recent_path_.clear();
  }
}

}  // namespace mostyle::app
