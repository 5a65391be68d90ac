// The export dialog (ui/panels/export_dialog.h) and its job (ui/model/export_job.h) over a loaded pair, with
// no window: the file's frame rate and frames, the confirmation before an overwrite, the export
// on its own thread, and the message that a new pair clears.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <catch2/catch.hpp>

#include "engine/kinematics/units.h"
#include <imgui.h>
#include <imgui_internal.h>  // ImGui::FindWindowByName

#include "engine/io/bvh/bvh_read.h"
#include "engine/base/job_control.h"
#include "engine/io/motion_file.h"
#include "engine/kinematics/kinematics.h"
#include "tests/test_data.h"
#include "tests/ui/imgui_frame.h"
#include "tests/ui/loaded_takes.h"
#include "ui/panels/export_dialog.h"
#include "ui/panels/files_panel.h"
#include "ui/panels/metrics_panel.h"
#include "ui/model/export_job.h"

using namespace mostyle;
using namespace mostyle::ui;
using test::LoadedTakes;
namespace fs = std::filesystem;

namespace {

using Pressed = ExportDialog::Pressed;

// A file in the temporary folder, removed before and after the test.
struct TempFile {
  std::string path;
  explicit TempFile(const std::string& name) : path((fs::temp_directory_path() / name).string()) { fs::remove(path); }
  ~TempFile() { fs::remove(path); }
};

void set_path(ExportDialog& dialog, const std::string& path) {
  ExportSettings& s = dialog.settings();
  path.copy(s.path, sizeof s.path - 1);
  s.path[std::min(path.size(), sizeof s.path - 1)] = '\0';
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Export with the dialog's settings, waiting for its thread; the written clip.
Clip export_and_read(ExportDialog& dialog, const std::string& path) {
  set_path(dialog, path);
  REQUIRE(dialog.press_export() == Pressed::kStarted);
  dialog.job().wait();
  dialog.poll();
  INFO(dialog.status().message);
  REQUIRE(dialog.status().ok);
  return read_bvh_file(path);
}

}  // namespace

TEST_CASE("export dialog: at 60 fps the file has twice the blend's frames less one, at 30 the blend's own") {
  LoadedTakes s;
  REQUIRE(s.engine.result() != nullptr);
  const int blend_frames = static_cast<int>(s.engine.result()->motion.world.rows());
  REQUIRE(s.engine.snapshot().prepared->fps == 30.0);
  ExportDialog dialog(s.engine);
  dialog.poll();
  TempFile file("mostyle_export_dialog_rate.bvh");

  dialog.settings().rate = ExportRate::k60;
  const Clip at_60 = export_and_read(dialog, file.path);
  CHECK(at_60.frames() == 2 * blend_frames - 1);
  CHECK(at_60.fps() == Approx(60.0));
  // Where it went, the rate, and how closely the file follows the blend, in metric units.
  CHECK_THAT(dialog.status().message, Catch::Contains("mostyle_export_dialog_rate.bvh"));
  CHECK_THAT(dialog.status().message, Catch::Contains("at 60 fps"));
  CHECK_THAT(dialog.status().message, Catch::Contains("m (worst joint and frame"));

  dialog.settings().rate = ExportRate::k30;
  fs::remove(file.path);
  const Clip at_30 = export_and_read(dialog, file.path);
  CHECK(at_30.frames() == blend_frames);

  // A's own rate: CMU's 120 fps.
  dialog.settings().rate = ExportRate::kSource;
  fs::remove(file.path);
  const Clip at_source = export_and_read(dialog, file.path);
  CHECK(at_source.fps() == Approx(120.0));
  CHECK(at_source.frames() == 4 * (blend_frames - 1) + 1);

  // A rate the export refuses: said in a sentence, nothing written.
  dialog.settings().rate = ExportRate::kCustom;
  dialog.settings().custom_fps = 0.0;
  fs::remove(file.path);
  set_path(dialog, file.path);
  REQUIRE(dialog.press_export() == Pressed::kStarted);
  dialog.job().wait();
  dialog.poll();
  CHECK_FALSE(dialog.status().ok);
  CHECK_THAT(dialog.status().message, Catch::Contains("frame rate"));
  CHECK_FALSE(fs::exists(file.path));
}

TEST_CASE("export dialog: an in and an out point give the frames between them, both included") {
  LoadedTakes s;
  ExportDialog dialog(s.engine);
  dialog.poll();  // the range starts as all of the blend
  REQUIRE(s.engine.result() != nullptr);
  REQUIRE(s.engine.result()->motion.world.rows() > 61);  // over 2 s at 30 fps
  CHECK(dialog.settings().in_s == 0.0);
  CHECK(dialog.settings().out_s == Approx((s.engine.result()->motion.world.rows() - 1) / 30.0));
  TempFile file("mostyle_export_dialog_range.bvh");
  dialog.settings().range = ExportRange::kInOut;
  dialog.settings().in_s = 1.0;
  dialog.settings().out_s = 2.0;
  CHECK(export_and_read(dialog, file.path).frames() == 31);
  fs::remove(file.path);
  dialog.settings().rate = ExportRate::k60;
  CHECK(export_and_read(dialog, file.path).frames() == 61);
  // An out point past the blend is brought back inside it by the next poll.
  dialog.settings().out_s = 1e6;
  dialog.poll();
  CHECK(dialog.settings().out_s == Approx((s.engine.result()->motion.world.rows() - 1) / 30.0));
}

TEST_CASE("export dialog: the loop is written whole, so it repeats at any rate") {
  LoadedTakes s;
  s.state.document.controls.loop = true;
  s.engine.sync(s.state);
  REQUIRE(s.engine.result() != nullptr);
  REQUIRE(s.engine.result()->motion.loop.cycles >= 1);
  const int loop_frames = static_cast<int>(s.engine.result()->motion.world.rows());
  ExportDialog dialog(s.engine);
  dialog.poll();
  TempFile file("mostyle_export_dialog_loop.bvh");
  dialog.settings().range = ExportRange::kLoop;
  dialog.settings().rate = ExportRate::k60;
  CHECK(export_and_read(dialog, file.path).frames() == 2 * loop_frames);
  CHECK_THAT(dialog.status().message, Catch::Contains("loop"));
  // Without a loop, the loop cannot be asked for.
  s.state.document.controls.loop = false;
  s.engine.sync(s.state);
  fs::remove(file.path);
  set_path(dialog, file.path);
  CHECK(dialog.press_export() == Pressed::kFailed);
  CHECK_THAT(dialog.status().message, Catch::Contains("no loop"));
  CHECK_FALSE(fs::exists(file.path));
}

TEST_CASE("export dialog: an existing file is overwritten only once confirmed") {
  LoadedTakes s;
  ExportDialog dialog(s.engine);
  dialog.poll();
  TempFile file("mostyle_export_dialog_overwrite.bvh");
  { std::ofstream(file.path) << "old\n"; }
  set_path(dialog, file.path);
  CHECK(dialog.press_export() == Pressed::kConfirm);
  CHECK(dialog.confirming_overwrite());
  CHECK_FALSE(dialog.job().running());
  CHECK(read_text(file.path) == "old\n");
  // Keep it: nothing written, and Overwrite alone asks again.
  dialog.press_cancel();
  CHECK_FALSE(dialog.confirming_overwrite());
  CHECK(dialog.press_overwrite() == Pressed::kConfirm);
  CHECK(read_text(file.path) == "old\n");
  // Confirmed: written.
  CHECK(dialog.press_overwrite() == Pressed::kStarted);
  dialog.job().wait();
  dialog.poll();
  CHECK(dialog.status().ok);
  CHECK(read_text(file.path).rfind("HIERARCHY", 0) == 0);
  // The next export over it asks again.
  CHECK(dialog.press_export() == Pressed::kConfirm);
}

TEST_CASE("export dialog: its message clears when new takes load") {
  LoadedTakes s;
  ExportDialog dialog(s.engine);
  dialog.poll();
  TempFile file("mostyle_export_dialog_message.bvh");
  export_and_read(dialog, file.path);
  CHECK_FALSE(dialog.status().message.empty());
  const double ms = dialog.status().ms;
  CHECK(ms >= 0.0);
  s.engine.load(test::asset("motions/cmu142_walk_joy.bvh"), test::asset("motions/cmu142_walk_happy.bvh"));
  s.engine.wait_idle(s.state);
  REQUIRE(s.engine.error().empty());
  dialog.poll();
  CHECK(dialog.status().message.empty());
  CHECK_FALSE(dialog.status().ok);
  CHECK(dialog.status().ms == ms);  // the last export's time stays
  // A failure's sentence clears too.
  set_path(dialog, "/nonexistent/dir/out.bvh");
  REQUIRE(dialog.press_export() == Pressed::kStarted);
  dialog.job().wait();
  dialog.poll();
  CHECK_FALSE(dialog.status().message.empty());
  CHECK_FALSE(dialog.status().ok);
  s.engine.load(test::asset("motions/cmu142_walk_happy.bvh"), test::asset("motions/cmu142_walk_marching.bvh"));
  s.engine.wait_idle(s.state);
  dialog.poll();
  CHECK(dialog.status().message.empty());
}

TEST_CASE("export job: the job copies the blend, and a cancel before the solve writes nothing") {
  LoadedTakes s;
  TempFile file("mostyle_export_job_cancel.bvh");
  ExportOptions options;
  options.path = file.path;
  options.fps = s.engine.snapshot().prepared->fps;
  const ExportRequest request = make_export_request(s.engine, options);
  CHECK(request.options.path == fs::absolute(file.path).string());
  CHECK(request.world == s.engine.result()->motion.world);
  JobControl cancelled;
  cancelled.cancel = true;
  const ExportOutcome outcome = run_export(request, &cancelled);
  CHECK(outcome.cancelled);
  CHECK_FALSE(outcome.ok);
  CHECK_FALSE(fs::exists(file.path));
  // The job runs one export at a time and hands its outcome over once.
  ExportJob job;
  CHECK(job.start(request));
  job.wait();
  ExportOutcome done;
  CHECK(job.take_outcome(&done));
  CHECK(done.ok);
  CHECK(done.frames == s.engine.result()->motion.world.rows());
  CHECK_FALSE(job.take_outcome(&done));
  CHECK(fs::exists(file.path));
  // The same export here and now, without a job.
  fs::remove(file.path);
  CHECK(run_export(request).ok);
  CHECK(read_bvh_file(file.path).frames() == s.engine.result()->motion.world.rows());
}

TEST_CASE("export dialog: the window draws in every mode, and the files panel opens it") {
  LoadedTakes s;
  test::HeadlessImGui imgui;
  FilesPanel files(s.engine, test::asset("motions"));
  TempFile file("mostyle_export_dialog_window.bvh");
  set_path(files.export_dialog(), file.path);
  auto frame = [&]() {
    imgui.begin_frame();
    files.draw(s.state);
    return imgui.end_frame();
  };
  frame();
  CHECK(ImGui::FindWindowByName(kExportDialogTitle) == nullptr);  // closed until asked for
  command_open_export(s.state);
  CHECK(frame() > 0);
  const ImGuiWindow* window = ImGui::FindWindowByName(kExportDialogTitle);
  REQUIRE(window != nullptr);
  CHECK(window->Active);
  ExportDialog& dialog = files.export_dialog();
  for (ExportRange range : {ExportRange::kAll, ExportRange::kInOut, ExportRange::kLoop}) {
    dialog.settings().range = range;
    dialog.settings().range_in_frames = range == ExportRange::kInOut;
    CHECK(frame() > 0);
  }
  dialog.settings().range = ExportRange::kInOut;
  dialog.settings().range_in_frames = false;
  dialog.settings().rate = ExportRate::kCustom;
  CHECK(frame() > 0);
  dialog.settings().range = ExportRange::kAll;
  dialog.settings().rate = ExportRate::k30;
  // An export running under the window, then its outcome in both places.
  REQUIRE(dialog.press_export() == Pressed::kStarted);
  CHECK(frame() > 0);
  dialog.job().wait();
  frame();
  CHECK(dialog.status().ok);
  CHECK_FALSE(dialog.status().message.empty());
  CHECK(fs::exists(file.path));
  // Asking before an overwrite, drawn.
  CHECK(dialog.press_export() == Pressed::kConfirm);
  CHECK(frame() > 0);
  CHECK(dialog.confirming_overwrite());
  CHECK(s.state.view.show_export);
}

TEST_CASE("export dialog: a palette's mix exports whole or from an in to an out point") {
  LoadedTakes s;
  s.engine.load_files({test::asset("motions/cmu142_walk_happy.bvh"), test::asset("motions/cmu142_walk_marching.bvh"),
                        test::asset("motions/cmu142_walk_joy.bvh")});
  s.engine.wait_idle(s.state);
  REQUIRE(s.engine.takes() != nullptr);
  const MixResult* mix = s.engine.result_view().mix();
  REQUIRE(mix != nullptr);
  const int mix_frames = static_cast<int>(mix->motion.world.rows());
  REQUIRE(mix_frames > 61);
  ExportDialog dialog(s.engine);
  dialog.poll();
  // The range is all of the mix, not 0 to 0.
  CHECK(dialog.settings().in_s == 0.0);
  CHECK(dialog.settings().out_s == Approx((mix_frames - 1) / 30.0));
  TempFile file("mostyle_export_dialog_palette.bvh");
  dialog.settings().rate = ExportRate::k30;
  CHECK(export_and_read(dialog, file.path).frames() == mix_frames);
  CHECK_THAT(dialog.status().message, Catch::Contains("The skeleton of cmu142_walk_happy.bvh"));
  // From 1 s to 2 s: 31 frames at 30 fps; the overwrite asks first and then replaces the file.
  dialog.settings().range = ExportRange::kInOut;
  dialog.settings().in_s = 1.0;
  dialog.settings().out_s = 2.0;
  dialog.poll();  // the points stay inside the mix: unchanged here
  CHECK(dialog.settings().out_s == 2.0);
  REQUIRE(dialog.press_export() == Pressed::kConfirm);
  REQUIRE(dialog.press_overwrite() == Pressed::kStarted);
  dialog.job().wait();
  dialog.poll();
  REQUIRE(dialog.status().ok);
  CHECK(read_bvh_file(file.path).frames() == 31);
  // The dialog draws in palette mode, with the reference's words (an auto-sized window shows
  // from its second frame).
  test::HeadlessImGui imgui;
  s.state.view.show_export = true;
  int drawn = 0;
  for (int frame = 0; frame < 2; ++frame) {
    imgui.begin_frame();
    dialog.draw(s.state);
    drawn = imgui.end_frame();
  }
  CHECK(drawn > 0);
}

TEST_CASE("export dialog: the format is the file's extension, glTF and FBX exports read back as the same blend") {
  CHECK(export_format("blend.bvh") == ExportFormat::kBvh);
  CHECK(export_format("blend.fbx") == ExportFormat::kFbx);
  CHECK(export_format("blend.FBX") == ExportFormat::kFbx);
  CHECK(export_format("blend.txt") == ExportFormat::kBvh);
  CHECK(with_export_format("out/blend.bvh", ExportFormat::kFbx) == "out/blend.fbx");
  CHECK(with_export_format("out/blend.glb", ExportFormat::kFbx) == "out/blend.fbx");
  CHECK(with_export_format("out/blend.fbx", ExportFormat::kGltf) == "out/blend.glb");
  CHECK(with_export_format("blend", ExportFormat::kFbx) == "blend.fbx");
  CHECK(export_format("blend.GLB") == ExportFormat::kGltf);
  CHECK(export_format("blend.gltf") == ExportFormat::kGltf);
  CHECK(with_export_format("out/blend.bvh", ExportFormat::kGltf) == "out/blend.glb");
  CHECK(with_export_format("out/blend.glb", ExportFormat::kBvh) == "out/blend.bvh");
  CHECK(with_export_format("blend.gltf", ExportFormat::kGltf) == "blend.gltf");
  CHECK(with_export_format("blend", ExportFormat::kGltf) == "blend.glb");
  CHECK(with_export_format("", ExportFormat::kGltf).empty());

  LoadedTakes s;
  REQUIRE(s.engine.result() != nullptr);
  ExportDialog dialog(s.engine);
  dialog.poll();
  TempFile bvh("mostyle_export_dialog_format.bvh"), glb("mostyle_export_dialog_format.glb"),
      fbx("mostyle_export_dialog_format.fbx");
  dialog.settings().rate = ExportRate::k30;
  const Clip as_bvh = export_and_read(dialog, bvh.path);
  for (const std::string& path : {glb.path, fbx.path}) {
    INFO(path);
    set_path(dialog, path);
    REQUIRE(dialog.press_export() == Pressed::kStarted);
    dialog.job().wait();
    dialog.poll();
    INFO(dialog.status().message);
    REQUIRE(dialog.status().ok);
    const Clip written = read_motion_file(path);
    REQUIRE(written.frames() == as_bvh.frames());
    CHECK(written.fps() == as_bvh.fps());
    // In metres: glTF is written in them whatever the take's unit (FBX keeps the take's).
    const double a_metres = metres_per_unit(as_bvh), b_metres = metres_per_unit(written);
    REQUIRE(a_metres > 0.0);
    REQUIRE(b_metres > 0.0);
    const Eigen::MatrixXd a = joint_positions(as_bvh) * a_metres, b = joint_positions(written) * b_metres;
    double worst = 0;
    for (size_t i = 0; i < as_bvh.skeleton.joints.size(); ++i) {
      if (as_bvh.skeleton.joints[i].end_site) continue;
      const int j = written.skeleton.find(as_bvh.skeleton.joints[i].name);
      REQUIRE(j >= 0);
      worst = std::max(worst, (a.middleCols(3 * i, 3) - b.middleCols(3 * j, 3)).rowwise().norm().maxCoeff());
    }
    CHECK(worst < 1e-3 * a_metres);  // a thousandth of a file unit (cm-like CMU units): float32 keys
  }
}

TEST_CASE("export dialog: the file is named after the result, a blend, a mix or a transfer, as the metrics say") {
  CHECK(export_name_for("blend.bvh", "mix") == "mix.bvh");
  CHECK(export_name_for("mix.glb", "transfer") == "transfer.glb");
  CHECK(export_name_for("transfer", "blend") == "blend");
  CHECK(export_name_for("walk.bvh", "mix") == "walk.bvh");          // the animator's own name
  CHECK(export_name_for("out/blend.bvh", "mix") == "out/blend.bvh");  // a folder chosen: a name chosen
  CHECK(std::string(result_name(2, false)) == "blend");
  CHECK(std::string(result_name(2, true)) == "transfer");  // a pair's transfer: B's style on A
  CHECK(std::string(result_name(3, false)) == "mix");

  LoadedTakes s;
  test::HeadlessImGui imgui;
  FilesPanel files(s.engine, test::asset("motions"));
  auto frame = [&]() {
    imgui.begin_frame();
    s.engine.poll(s.state);
    files.draw(s.state);
    s.engine.sync(s.state);
    imgui.end_frame();
  };
  frame();
  CHECK(std::string(files.export_dialog().settings().path) == "blend.bvh");
  s.engine.load_files({test::asset("motions/cmu142_walk_happy.bvh"), test::asset("motions/cmu142_walk_marching.bvh"),
                        test::asset("motions/cmu142_walk_joy.bvh")});
  s.engine.wait_idle(s.state);
  REQUIRE(s.engine.takes() != nullptr);
  frame();
  CHECK(std::string(files.export_dialog().settings().path) == "mix.bvh");
  CHECK(gather_metrics(s.engine, s.state.document.controls.transfer).result == "mix");
  s.state.document.controls.transfer = true;
  frame();
  CHECK(std::string(files.export_dialog().settings().path) == "transfer.bvh");
  CHECK(gather_metrics(s.engine, s.state.document.controls.transfer).result == "transfer");
  // A name typed stays, whatever the mode.
  set_path(files.export_dialog(), "proud.glb");
  s.state.document.controls.transfer = false;
  frame();
  CHECK(std::string(files.export_dialog().settings().path) == "proud.glb");
}

TEST_CASE("export dialog: the in and out fields take a frame typed after one click") {
  LoadedTakes s;
  test::HeadlessImGui imgui;
  ImGuiIO& io = ImGui::GetIO();
  constexpr int kEnter = 257;
  io.KeyMap[ImGuiKey_Enter] = kEnter;
  ExportDialog dialog(s.engine);
  s.state.view.show_export = true;
  dialog.settings().range = ExportRange::kInOut;
  dialog.settings().range_in_frames = true;
  auto frame = [&]() {
    imgui.begin_frame();
    dialog.draw(s.state);
    imgui.end_frame();
  };
  frame();
  frame();
  const double out_before = dialog.settings().out_s;
  REQUIRE(out_before * 30.0 > 40.0);
  // The mouse over the dialog until ImGui gives the In field the hover.
  const ImGuiWindow* window = ImGui::FindWindowByName(kExportDialogTitle);
  REQUIRE(window != nullptr);
  const ImGuiID in_id = ImHashStr("In##frames", 0, window->ID);
  bool found = false;
  const ImRect r = window->Rect();
  for (float y = r.Min.y + 2.0f; y < r.Max.y && !found; y += 4.0f)
    for (float x = r.Min.x + 2.0f; x < r.Max.x && !found; x += 8.0f) {
      io.MousePos = ImVec2(x, y);
      frame();
      found = GImGui->HoveredId == in_id;
    }
  REQUIRE(found);
  io.MouseDown[0] = true;  // one plain click
  frame();
  io.MouseDown[0] = false;
  frame();
  for (char c : std::string("40")) io.AddInputCharacter(static_cast<unsigned>(c));  // over the 0 it selected
  frame();
  io.KeysDown[kEnter] = true;
  frame();
  io.KeysDown[kEnter] = false;
  frame();
  CHECK(dialog.settings().in_s * 30.0 == Approx(40.0));
  CHECK(dialog.settings().out_s == out_before);
}
