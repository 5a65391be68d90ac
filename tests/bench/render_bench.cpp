// Viewport and editor frame cost with OSMesa (llvmpipe) at 1280x720: three CMU skeletons
// (31 joints + 7 End Sites each), as the editor shows them. Each iteration ends in glFinish,
// so the time is the frame's full CPU + rasterisation cost.
#include <benchmark/benchmark.h>

#include <cmath>

#include <imgui.h>

#include "app/editor/editor.h"
#include "app/editor/imgui_context.h"
#include "engine/io/bvh/bvh_read.h"
#include "engine/kinematics/kinematics.h"
#include "engine/kinematics/units.h"
#include "render/gl.h"
#include "render/render_target.h"
#include "render/scene_renderer.h"
#include "render/skeleton_pose.h"
#include "render/skeleton_renderer.h"
#include "tests/render/osmesa_context.h"

namespace {

using namespace mostyle;

const glm::ivec2 kSize(1280, 720);
const char* const kTakes[] = {"cmu142_walk_happy.bvh", "cmu142_walk_marching.bvh", "cmu142_walk_joy.bvh"};

std::string asset(const char* name) { return std::string(MOSTYLE_ASSETS_DIR) + "/motions/" + name; }

struct LoadedTake {
  Eigen::MatrixXd positions;
  std::vector<int> parents;
  float size = 1.0f;
};

// The scene at `frame`: the takes side by side along x, as the editor places them.
render::Scene scene_at(const std::vector<LoadedTake>& takes, int frame) {
  render::Scene scene;
  const glm::vec3 colors[] = {{0.96f, 0.60f, 0.28f}, {0.36f, 0.64f, 0.97f}, {0.48f, 0.82f, 0.46f}};
  for (size_t i = 0; i < takes.size(); ++i) {
    render::SkeletonPose pose;
    pose.label = kTakes[i];
    pose.color = colors[i];
    pose.positions = render::positions_at(takes[i].positions, frame % static_cast<int>(takes[i].positions.rows()));
    for (glm::vec3& p : pose.positions) p.x += (static_cast<float>(i) - 1.0f) * 0.55f * takes[i].size;
    pose.parents = takes[i].parents;
    pose.size = takes[i].size;
    render::mark_ground_contacts(&pose, 0.0f, 0.04f * pose.size);
    scene.skeletons.push_back(std::move(pose));
  }
  return scene;
}

std::vector<LoadedTake> load_takes() {
  std::vector<LoadedTake> takes;
  for (const char* name : kTakes) {
    Clip clip = read_bvh_file(asset(name));
    LoadedTake t;
    t.positions = joint_positions(clip);
    t.parents = render::parent_indices(clip.skeleton);
    t.size = static_cast<float>(mostyle::motion_height(t.positions));
    takes.push_back(std::move(t));
  }
  return takes;
}

render::OrbitCamera framing_camera(const render::Scene& scene) {
  render::OrbitCamera camera;
  camera.yaw = 0.6f;
  camera.pitch = 0.22f;
  render::Bounds b;
  for (const render::SkeletonPose& pose : scene.skeletons) b.extend(render::pose_bounds(pose));
  camera.frame(b, 16.0f / 9.0f, 0.62f);
  return camera;
}

// The skeletons alone (depth cleared, no floor): the part that grows with the joint count.
void BM_SkeletonsDraw(benchmark::State& state) {
  test::OsMesaContext gl(kSize);
  if (!gl.ok()) {
    state.SkipWithError(gl.error().c_str());
    return;
  }
  std::vector<LoadedTake> takes = load_takes();
  render::SkeletonRenderer renderer;
  render::OrbitCamera camera = framing_camera(scene_at(takes, 0));
  const glm::mat4 projection = camera.projection(16.0f / 9.0f);
  glViewport(0, 0, kSize.x, kSize.y);
  int frame = 0;
  for (auto _ : state) {
    render::Scene scene = scene_at(takes, frame++);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    renderer.draw(scene.skeletons, camera.view(), projection);
    glFinish();
  }
  state.counters["joints"] = static_cast<double>(3 * takes[0].parents.size());
}
BENCHMARK(BM_SkeletonsDraw)->Unit(benchmark::kMillisecond)->UseRealTime();

// The whole viewport: backdrop, floor, shadows, contact rings, skeletons. args: MSAA samples.
void BM_ViewportDraw(benchmark::State& state) {
  test::OsMesaContext gl(kSize);
  if (!gl.ok()) {
    state.SkipWithError(gl.error().c_str());
    return;
  }
  std::vector<LoadedTake> takes = load_takes();
  render::SceneRenderer renderer;
  render::RenderTarget target;
  const int samples = static_cast<int>(state.range(0));
  target.resize(kSize, samples);
  render::OrbitCamera camera = framing_camera(scene_at(takes, 0));
  int frame = 0;
  for (auto _ : state) {
    render::Scene scene = scene_at(takes, frame++);
    if (samples > 1) {  // as the editor does: one sample draws straight into the window
      target.bind();
      renderer.draw(scene, camera, kSize, {});
      target.resolve_to(0, kSize);
    } else {
      renderer.draw(scene, camera, kSize, {});
    }
    glFinish();
  }
  state.counters["joints"] = static_cast<double>(3 * takes[0].parents.size());
  state.counters["samples"] = target.samples();
}
BENCHMARK(BM_ViewportDraw)->Arg(1)->Arg(4)->Unit(benchmark::kMillisecond)->UseRealTime();

// The editor's whole frame offscreen: ImGui panels and labels, playback, the viewport.
void BM_EditorFrame(benchmark::State& state) {
  test::OsMesaContext gl(kSize);
  if (!gl.ok()) {
    state.SkipWithError(gl.error().c_str());
    return;
  }
  app::ImGuiContextScope imgui(false);
  app::EditorOptions options;
  for (const char* name : kTakes) options.files.push_back(asset(name));
  app::Editor editor(options);
  editor.wait_for_engine();  // A, B and the blend on screen
  editor.init_graphics();
  ImGuiIO& io = ImGui::GetIO();
  // Arg 1: a decomposition is kept running on the worker the whole time (k alternates), as
  // when the animator drags the k slider; the frame must not wait for it.
  const bool decomposing = state.range(0) != 0;
  int busy = 0, frames = 0;
  for (auto _ : state) {
    if (decomposing && editor.engine().status().stage == WorkerStage::kIdle) {
      editor.state().document.parameters.components = editor.state().document.parameters.components == 30 ? 32 : 30;  // ~0.3 s each
    }
    set_pair_alpha(editor.state().document, 0.5 + 0.4 * std::sin(0.05 * frames));  // re-blended each frame
    io.DisplaySize = ImVec2(static_cast<float>(kSize.x), static_cast<float>(kSize.y));
    io.DeltaTime = 1.0f / 60.0f;
    editor.frame(app::FrameInput{kSize, 1.0f / 60.0f});
    glFinish();
    busy += editor.engine().status().stage != WorkerStage::kIdle ? 1 : 0;
    ++frames;
  }
  state.counters["skeletons"] = static_cast<double>(editor.state().shown.size());
  state.counters["busy_frames"] = frames > 0 ? static_cast<double>(busy) / frames : 0.0;
  editor.shutdown_graphics();
}
BENCHMARK(BM_EditorFrame)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
