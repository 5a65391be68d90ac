#include "app/editor.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <limits>
#include <stdexcept>

#include <imgui.h>
#include <imgui_impl_opengl3.h>

#include "engine/bvh_io.h"
#include "engine/error.h"
#include "engine/kinematics.h"
#include "render/gl.h"
#include "render/skeleton_pose.h"
#include "ui/playback_panel.h"
#include "ui/takes_panel.h"
#include "ui/viewport_overlay.h"

namespace mostyle::app {
namespace {

// Take colours, in load order: warm orange, sky blue, green, pink (sRGB).
const glm::vec3 kTakeColors[] = {
    {0.96f, 0.60f, 0.28f}, {0.36f, 0.64f, 0.97f}, {0.48f, 0.82f, 0.46f}, {0.90f, 0.48f, 0.72f}};

// Joints closer than this to the floor (times the skeleton's size) get a contact ring: a
// display stand-in until the panels show the pipeline's contacts (engine/foot_contact.h).
constexpr float kContactTolerance = 0.04f;
// How much of the view the skeletons fill when framed: room for the floor and the panels.
constexpr float kFrameFill = 0.62f;
// Viewport multisampling of screenshots, whatever the renderer.
constexpr int kScreenshotSamples = 4;
// Side-by-side spacing of takes, times the largest size.
constexpr float kTakeSpacing = 0.55f;

// A ROOT that never moves while a child swings far from it (Bandai's joint_Root, on the floor
// under the hips) is a rig's reference, not a body part: drawing its bone would show a stick
// from the floor to the pelvis. Such roots are hidden. O(frames * joints).
std::vector<std::uint8_t> static_reference_roots(const Eigen::MatrixXd& positions,
                                                 const std::vector<int>& parents, float size) {
  std::vector<std::uint8_t> hidden(parents.size(), 0);
  auto at = [&](Eigen::Index frame, size_t joint) {
    return Eigen::Vector3d(positions.row(frame).segment<3>(3 * static_cast<Eigen::Index>(joint)));
  };
  for (size_t root = 0; root < parents.size(); ++root) {
    if (parents[root] != -1) continue;
    double travel = 0.0, reach = 0.0;
    for (Eigen::Index f = 0; f < positions.rows(); ++f) {
      travel = std::max(travel, (at(f, root) - at(0, root)).norm());
      for (size_t c = 0; c < parents.size(); ++c)
        if (parents[c] == static_cast<int>(root)) reach = std::max(reach, (at(f, c) - at(f, root)).norm());
    }
    if (travel < 1e-3 * size && reach > 0.3 * size) hidden[root] = 1;
  }
  return hidden;
}

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

ui::Take load_take(const std::string& path, int index) {
  ui::Take take;
  take.path = path;
  take.label = std::filesystem::path(path).stem().string();
  take.color = kTakeColors[static_cast<size_t>(index) % std::size(kTakeColors)];
  try {
    auto clip = std::make_shared<Clip>(read_bvh_file(path, &take.warnings));
    if (clip->frames() == 0) throw InputError(path + ": no frames");
    take.positions = joint_positions(*clip);
    take.parents = render::parent_indices(clip->skeleton);
    take.size = render::clip_size(take.positions);
    if (!(take.size > 0.0f)) take.size = std::max(render::clip_bounds(take.positions).radius(), 1.0f);
    take.hidden = static_reference_roots(take.positions, take.parents, take.size);
    take.clip = std::move(clip);
  } catch (const InputError& e) {
    take.error = e.what();
  } catch (const std::exception& e) {  // our bug, but still not a crash
    take.error = path + ": " + e.what();
  }
  return take;
}

}  // namespace

Editor::Editor(const EditorOptions& options) {
  state_.parameters = options.initial.parameters;
  load_takes(options.files.empty() ? default_motion_files() : options.files);
  place_takes();
  if (const ui::Take* reference = state_.reference_take()) {
    state_.playback.time_s = (options.initial.frame + 0.5) / reference->clip->fps();
  }
  // The panels, drawn in this order each frame. New panels go here.
  add_panel(std::make_unique<ui::TakesPanel>());
  add_panel(std::make_unique<ui::PlaybackPanel>());
}

Editor::~Editor() = default;

void Editor::load_takes(const std::vector<std::string>& files) {
  for (size_t i = 0; i < files.size(); ++i) {
    state_.takes.push_back(load_take(files[i], static_cast<int>(i)));
    const ui::Take& t = state_.takes.back();
    if (!t.error.empty()) std::fprintf(stderr, "mostyle: %s\n", t.error.c_str());
  }
}

// Puts the takes side by side on a common floor: each starts where the first starts, moved
// sideways (across the first take's direction of travel) and down to stand on y = 0.
void Editor::place_takes() {
  const ui::Take* reference = state_.reference_take();
  if (reference == nullptr) return;
  float largest = 0.0f;
  for (const ui::Take& t : state_.takes)
    if (t.ok()) largest = std::max(largest, t.size);

  const Eigen::Vector2d travel = travel_direction(*reference);
  const Eigen::Vector2d side = travel.isZero() ? Eigen::Vector2d(1.0, 0.0) : Eigen::Vector2d(travel.y(), -travel.x());

  int count = 0;
  for (const ui::Take& t : state_.takes) count += t.ok() ? 1 : 0;
  int slot = 0;
  for (ui::Take& t : state_.takes) {
    if (!t.ok()) continue;
    const double lateral = (slot - 0.5 * (count - 1)) * kTakeSpacing * largest;
    ++slot;
    double lowest = std::numeric_limits<double>::max();
    for (size_t j = 0; j < t.parents.size(); ++j)
      if (t.hidden.empty() || !t.hidden[j])
        lowest = std::min(lowest, t.positions.col(3 * static_cast<Eigen::Index>(j) + 1).minCoeff());
    const Eigen::Vector3d start = body_centre(t, 0);
    const Eigen::Vector3d shift(-start.x() + lateral * side.x(), -lowest, -start.z() + lateral * side.y());
    for (Eigen::Index j = 0; 3 * j < t.positions.cols(); ++j) {
      for (int a = 0; a < 3; ++a) t.positions.col(3 * j + a).array() += shift[a];
    }
  }
}

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
    if (state_.view.contacts) render::mark_ground_contacts(&pose, 0.0f, kContactTolerance * t.size);
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

void Editor::frame(const FrameInput& input) {
  if (!graphics_ready_) throw std::logic_error("Editor::frame before init_graphics");
  const glm::ivec2 size = glm::max(input.framebuffer_size, glm::ivec2(1));
  const float aspect = static_cast<float>(size.x) / static_cast<float>(size.y);

  ImGui_ImplOpenGL3_NewFrame();
  ImGui::NewFrame();

  // Playback, then the pose at the playhead.
  ui::Playback& playback = state_.playback;
  if (const ui::Take* reference = state_.reference_take(); reference && playback.playing) {
    playback.time_s += static_cast<double>(input.delta_s) * playback.speed;
    const double length = (reference->frames() - 1) / reference->clip->fps();
    if (playback.time_s > length) playback.time_s = playback.loop ? 0.0 : length;
  }
  build_scene();

  // Camera: framed once on the first poses, then the mouse and the follow mode move it.
  if (!camera_framed_ || state_.view.request_reframe) {
    frame_camera(aspect);
    camera_framed_ = !scene_.skeletons.empty();
    state_.view.request_reframe = false;
  }
  ui::apply_camera_input(camera_);
  if (state_.view.follow && !scene_.skeletons.empty()) {
    glm::vec3 centre(0.0f);
    for (const render::SkeletonPose& pose : scene_.skeletons) centre += render::pose_bounds(pose).center();
    camera_.follow(centre / static_cast<float>(scene_.skeletons.size()), input.delta_s);
  }

  for (auto& panel : panels_) panel->draw(state_);
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
}

}  // namespace mostyle::app
