#include "app/editor.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <limits>
#include <stdexcept>

#include <imgui.h>
#include <imgui_impl_opengl3.h>

#include "render/gl.h"
#include "render/skeleton_pose.h"
#include "ui/playback_panel.h"
#include "ui/components_panel.h"
#include "ui/dtw_panel.h"
#include "ui/files_panel.h"
#include "ui/metrics_panel.h"
#include "ui/parameters_panel.h"
#include "ui/takes_panel.h"
#include "ui/viewport_overlay.h"

namespace mostyle::app {
namespace {

// Joints closer than this to the floor (times the skeleton's size) get a contact ring when a
// take carries no contacts of the pipeline's own (engine/foot_contact.h).
constexpr float kContactTolerance = 0.04f;
// How much of the view the skeletons fill when framed: room for the floor and the panels.
constexpr float kFrameFill = 0.62f;
// Viewport multisampling of screenshots, whatever the renderer.
constexpr int kScreenshotSamples = 4;

// Mean of the visible joints at `frame`: where the body is (joint 0 may be a static ROOT).
Eigen::Vector3d body_centre(const ui::Take& take, Eigen::Index frame) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int count = 0;
  for (size_t j = 0; j < take.parents.size(); ++j) {
    if (!take.hidden.empty() && take.hidden[j]) continue;
    sum += take.positions.row(frame).segment<3>(3 * static_cast<Eigen::Index>(j)).transpose();
    ++count;
  }
  return count > 0 ? Eigen::Vector3d(sum / count) : sum;
}

// Horizontal direction of travel over the take (x, z); zero when it walks in place.
Eigen::Vector2d travel_direction(const ui::Take& take) {
  Eigen::Vector3d d = body_centre(take, take.positions.rows() - 1) - body_centre(take, 0);
  Eigen::Vector2d horizontal(d.x(), d.z());
  return horizontal.norm() > 0.25 * take.size ? Eigen::Vector2d(horizontal.normalized()) : Eigen::Vector2d::Zero();
}

}  // namespace

Editor::Editor(const EditorOptions& options) : session_(std::make_unique<ui::BlendSession>()) {
  state_.parameters = options.initial.parameters;
  initial_frame_ = options.initial.frame;
  // The pair goes to the engine's worker: aligned, decomposed and blended off this thread.
  const std::vector<std::string> files = options.files.empty() ? default_motion_files() : options.files;
  session_->request_decomposition(state_);
  session_->load(files.empty() ? std::string() : files[0], files.size() > 1 ? files[1] : std::string());
  std::string folder = files.empty() ? std::string(".") : std::filesystem::path(files[0]).parent_path().string();
  if (folder.empty()) folder = ".";
  // The panels, drawn in this order each frame. New panels go here.
  add_panel(std::make_unique<ui::TakesPanel>());
  add_panel(std::make_unique<ui::ParametersPanel>(*session_));
  add_panel(std::make_unique<ui::FilesPanel>(*session_, folder));
  add_panel(std::make_unique<ui::DtwPanel>(*session_));
  add_panel(std::make_unique<ui::ComponentsPanel>(*session_));
  add_panel(std::make_unique<ui::MetricsPanel>(*session_));
  add_panel(std::make_unique<ui::PlaybackPanel>());
}

void Editor::update_engine() {
  session_->poll(state_);
  session_->update_blend(state_);
  const void* pair = session_->snapshot().prepared.get();
  if (pair != nullptr && pair != framed_pair_) {  // a new pair: frame it, start at --frame once
    framed_pair_ = pair;
    state_.view.request_reframe = true;
    if (const ui::Take* reference = state_.reference_take()) {
      const int frame = initial_frame_applied_ ? 0 : std::min(initial_frame_, std::max(reference->frames() - 1, 0));
      state_.playback.time_s = (frame + 0.5) / reference->rate();
      initial_frame_applied_ = true;
    }
  }
}

void Editor::wait_for_engine() {
  session_->wait_idle(state_);
  update_engine();
}

void Editor::drop_files(const std::vector<std::string>& paths) {
  auto& queue = session_->dropped();
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
  for (const ui::Take& t : state_.takes) {
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
  // A three-quarter view from the front of the first take's direction of travel.
  const ui::Take* reference = state_.reference_take();
  float heading = 0.0f;
  if (reference != nullptr) {
    const Eigen::Vector2d travel = travel_direction(*reference);
    if (!travel.isZero()) heading = static_cast<float>(std::atan2(travel.x(), travel.y()));
  }
  camera_.yaw = heading + 0.65f;
  camera_.pitch = 0.22f;
  camera_.frame(b, aspect, kFrameFill);
}

bool Editor::animating() const {
  const WorkerStatus status = session_->status();
  return state_.playback.playing || status.stage != WorkerStage::kIdle || status.pending || session_->sweeping() ||
         !session_->dropped().empty();
}

void Editor::frame(const FrameInput& input) {
  if (!graphics_ready_) throw std::logic_error("Editor::frame before init_graphics");
  const glm::ivec2 size = glm::max(input.framebuffer_size, glm::ivec2(1));
  const float aspect = static_cast<float>(size.x) / static_cast<float>(size.y);

  ImGui_ImplOpenGL3_NewFrame();
  ImGui::NewFrame();

  const auto cpu_start = std::chrono::steady_clock::now();
  update_engine();  // the worker's latest pair and decomposition, never waiting for it

  // Playback on A's aligned timeline.
  ui::Playback& playback = state_.playback;
  if (const ui::Take* reference = state_.reference_take(); reference && playback.playing) {
    playback.time_s += static_cast<double>(input.delta_s) * playback.speed;
    const double length = (reference->frames() - 1) / reference->rate();
    if (playback.time_s > length) playback.time_s = playback.loop ? 0.0 : length;
  }

  // Panels first: an alpha moved in this frame is blended and drawn in this frame.
  for (auto& panel : panels_) panel->draw(state_);
  session_->update_blend(state_);
  build_scene();

  // Camera: framed once on the first poses, then the mouse and the follow mode move it.
  if (!camera_framed_ || state_.view.request_reframe) {
    frame_camera(aspect);
    camera_framed_ = !scene_.skeletons.empty();
    state_.view.request_reframe = scene_.skeletons.empty() && state_.view.request_reframe;
  }
  ui::apply_camera_input(camera_);
  if (state_.view.follow && !scene_.skeletons.empty()) {
    glm::vec3 centre(0.0f);
    for (const render::SkeletonPose& pose : scene_.skeletons) centre += render::pose_bounds(pose).center();
    camera_.follow(centre / static_cast<float>(scene_.skeletons.size()), input.delta_s);
  }

  if (state_.view.labels) ui::draw_skeleton_labels(scene_.skeletons, camera_);
  if (!deterministic_) {  // timings differ run to run: not in screenshots
    char status[96];
    std::snprintf(status, sizeof status, "viewport %.1f ms   %.0f fps", viewport_timer_->milliseconds(),
                  static_cast<double>(ImGui::GetIO().Framerate));
    ui::draw_viewport_status(status);
  }
  ImGui::Render();

  // The viewport: the scene into the multisampled target, resolved into the window (or, with
  // one sample, straight into the window).
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
  glViewport(0, 0, size.x, size.y);
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  // Shown by the metrics panel on the next frame; not in screenshots (they differ run to run).
  session_->frame_ms = deterministic_ ? -1.0f
                                      : std::chrono::duration<float, std::milli>(std::chrono::steady_clock::now() - cpu_start).count();
  session_->viewport_ms = deterministic_ ? -1.0f : viewport_timer_->milliseconds();
}

}  // namespace mostyle::app
