#include "ui/panels/export_dialog.h"
#include "ui/panels/theme.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <system_error>
#include <utility>

#include <imgui.h>

#include "engine/export/export_frames.h"
#include "engine/io/motion_file.h"
#include "engine/base/numbers.h"
#include "ui/panels/files_panel.h"

namespace mostyle::ui {
namespace fs = std::filesystem;
namespace {

constexpr float kFieldWidth = 120.0f;  // the rate and range fields, pixels
constexpr float kWrapWidth = 440.0f;   // sentences; a fixed width, since the window fits its contents

std::string absolute_path(const std::string& path) {
  std::error_code ec;
  const fs::path p = fs::absolute(fs::path(path), ec);
  return ec ? path : p.string();
}

void tooltip(const char* text) {
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", text);
}

void wrapped(const ImVec4& color, const std::string& text) {
  ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + kWrapWidth);
  ImGui::TextColored(color, "%s", text.c_str());
  ImGui::PopTextWrapPos();
}

}  // namespace

ExportFormat export_format(const std::string& path) {
  if (!is_motion_file(path)) return ExportFormat::kBvh;
  switch (motion_format(path)) {
    case MotionFormat::kGltf: return ExportFormat::kGltf;
    case MotionFormat::kFbx: return ExportFormat::kFbx;
    case MotionFormat::kBvh: break;
  }
  return ExportFormat::kBvh;
}

std::string with_export_format(const std::string& path, ExportFormat format) {
  if (path.empty() || export_format(path) == format) return path;
  const char* extension = format == ExportFormat::kGltf ? ".glb" : format == ExportFormat::kFbx ? ".fbx" : ".bvh";
  fs::path p(path);
  if (p.has_extension()) p.replace_extension(extension);
  else p += extension;
  return p.string();
}

std::string export_name_for(const std::string& path, const std::string& result) {
  const std::filesystem::path p(path);
  if (p.has_parent_path()) return path;
  const std::string stem = p.stem().string();
  if (stem != "blend" && stem != "mix" && stem != "transfer") return path;
  return result + p.extension().string();
}

double export_rate_fps(ExportRate rate, double source_fps, double custom_fps) {
  switch (rate) {
    case ExportRate::kSource: return source_fps;
    case ExportRate::k30: return 30.0;
    case ExportRate::k60: return 60.0;
    case ExportRate::k120: return 120.0;
    case ExportRate::kCustom: return custom_fps;
  }
  return custom_fps;
}

ExportDialog::ExportDialog(EngineLink& engine) : engine_(engine) {}

ExportOptions ExportDialog::options() const {
  const ExportSubject subject = export_subject(engine_);
  ExportOptions o;
  // A name alone goes beside the session (or the first take), as every file the editor writes.
  const fs::path typed(settings_.path);
  o.path = typed.is_relative() && !typed.empty() && !folder_.empty() ? (fs::path(folder_) / typed).string()
                                                                     : typed.string();
  o.fps = export_rate_fps(settings_.rate, subject.clip != nullptr ? subject.clip->fps() : 0.0, settings_.custom_fps);
  o.range = settings_.range;
  o.in_s = settings_.in_s;
  o.out_s = settings_.out_s;
  o.layout = settings_.layout;
  return o;
}

void ExportDialog::poll() {
  const ExportSubject subject = export_subject(engine_);
  if (subject.identity != seen_pair_) {
    seen_pair_ = subject.identity;
    confirm_ = false;
    status_.ok = false;  // it spoke of the previous takes
    status_.message.clear();
    reset_range_ = true;
    // Once per pair or palette: O(frames x channels) of the reference.
    if (subject.clip != nullptr) settings_.layout = default_channel_layout(*subject.clip);
  }
  if (subject.frames > 0) {
    const double length = motion_length_s(subject.frames, subject.working_fps);
    if (reset_range_) {
      settings_.in_s = 0.0;
      settings_.out_s = length;
      reset_range_ = false;
    }
    // The result's length follows the weights when the timing is mixed: the points stay inside it.
    settings_.out_s = std::clamp(settings_.out_s, 0.0, length);
    // Not while a point is typed: "2" on the way to "200" must not move the other point.
    settings_.in_s = std::clamp(settings_.in_s, 0.0, typing_range_ ? length : settings_.out_s);
  }
  ExportOutcome outcome;
  if (job_.take_outcome(&outcome)) {
    status_.ok = outcome.ok;
    status_.message = outcome.message;
    if (outcome.ok) status_.ms = outcome.ms;
  }
}

ExportDialog::Pressed ExportDialog::press_export() { return start(false); }
ExportDialog::Pressed ExportDialog::press_overwrite() { return start(true); }

void ExportDialog::press_cancel() {
  if (job_.running()) job_.cancel();
  confirm_ = false;
}

ExportDialog::Pressed ExportDialog::start(bool overwrite) {
  if (job_.running()) return Pressed::kBusy;
  ExportRequest request;
  try {
    request = make_export_request(engine_, options());
  } catch (const std::exception& e) {  // InputError: no file name, no blend, no loop
    confirm_ = false;
    status_.ok = false;
    status_.message = e.what();
    return Pressed::kFailed;
  }
  std::error_code ec;
  const bool exists = fs::exists(fs::path(request.options.path), ec);
  if (exists && !(overwrite && confirm_ && confirm_path_ == request.options.path)) {
    confirm_ = true;
    confirm_path_ = request.options.path;
    return Pressed::kConfirm;
  }
  confirm_ = false;
  // The last outcome is not this one's: neither the message nor one finished since the last poll.
  ExportOutcome stale;
  job_.take_outcome(&stale);
  status_.ok = false;
  status_.message.clear();
  job_.start(std::move(request));
  return Pressed::kStarted;
}

void ExportDialog::draw(EditorState& state) {
  folder_ = state.files_folder;
  poll();
  typing_range_ = false;  // until the in or out field drawn below is found active
  // When the result becomes another kind (a pair a palette, a mix a transfer), not while a name
  // is typed.
  const PreparedTakes* p = engine_.snapshot().prepared.get();
  const std::string result = p != nullptr ? result_name(p->size(), state.document.controls.transfer) : "";
  if (p != nullptr && result != named_result_) {
    named_result_ = result;
    const std::string named = export_name_for(settings_.path, result);
    std::snprintf(settings_.path, sizeof settings_.path, "%s", named.c_str());
  }
  if (!state.view.show_export) {
    shown_ = false;
    return;
  }
  if (!shown_ && !job_.running()) {  // opened anew: the last export's outcome was read where it was said
    status_.ok = false;
    status_.message.clear();
  }
  shown_ = true;
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(0.5f * display.x, 0.5f * display.y), ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
  bool open = true;
  const ImGuiWindowFlags flags =
      ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoSavedSettings;
  if (ImGui::Begin(kExportDialogTitle, &open, flags)) {
    draw_contents(state, &open);
    // Esc closes it, as every other dialog of the editor, unless it asks about an overwrite (Esc
    // keeps the file then) or a field is being typed in (Esc leaves the field first).
    const bool esc = ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape), false);
    if (esc && ImGui::IsWindowFocused(ImGuiFocusedFlags_RootAndChildWindows) && !ImGui::GetIO().WantTextInput) {
      if (confirm_) press_cancel();
      else open = false;
    }
  }
  ImGui::End();
  if (!open) {
    state.view.show_export = false;
    confirm_ = false;  // a closed dialog asks nothing (a running export goes on)
  }
}

void ExportDialog::draw_contents(EditorState& state, bool* open) {
  const ExportSubject subject = export_subject(engine_);
  const bool busy = job_.running();  // once: the job may end while the dialog is drawn
  // A path edited after the question was asked: the question was about another file.
  if (confirm_ && absolute_path(options().path) != confirm_path_) confirm_ = false;

  ImGui::BeginDisabled(busy);
  ExportFormat format = ExportFormat::kBvh;
  const bool enter = draw_file_fields(&format);
  draw_rate(subject);
  draw_range(state, subject);
  draw_channels(subject, format);
  ImGui::EndDisabled();
  draw_summary(subject);
  draw_actions(busy, enter, open);
  draw_status();
}

bool ExportDialog::draw_file_fields(ExportFormat* format_shown) {
  // The file.
  ImGui::SetNextItemWidth(kWrapWidth - 60.0f);
  const bool enter = ImGui::InputText("File", settings_.path, sizeof settings_.path, ImGuiInputTextFlags_EnterReturnsTrue);
  if (ImGui::IsItemHovered()) {
    std::error_code ec;
    ImGui::SetTooltip("The file to write (.bvh, .glb / .gltf for glTF, .fbx); a name alone goes in %s.\nEnter exports.",
                      folder_.empty() ? fs::current_path(ec).string().c_str() : folder_.c_str());
  }
  // The format: the file's extension, which these buttons change.
  const ExportFormat format = export_format(settings_.path);
  *format_shown = format;
  auto format_button = [&](ExportFormat f, const char* label, const char* tip) {
    if (ImGui::RadioButton(label, format == f) && format != f) {
      const std::string path = with_export_format(settings_.path, f);
      std::snprintf(settings_.path, sizeof settings_.path, "%s", path.c_str());
    }
    tooltip(tip);
  };
  format_button(ExportFormat::kBvh, "BVH", "BVH on take A's skeleton, A's rotation orders and channels");
  ImGui::SameLine();
  format_button(ExportFormat::kGltf, "glTF (.glb)",
                "glTF 2.0: A's skeleton as an armature (nodes and a skin), one animation (root\n"
                "translation, rotations as quaternions), for game engines, three.js and Blender");
  ImGui::SameLine();
  format_button(ExportFormat::kFbx, "FBX",
                "Binary FBX 7.4: A's skeleton as an armature of limb nodes, one take (root translation,\n"
                "rotations as Euler curves in each joint's order, at the file's frame rate), for\n"
                "Blender, Maya, MotionBuilder, Unity and Unreal");
  return enter;
}

void ExportDialog::draw_rate(const ExportSubject& subject) {
  const double working = subject.working_fps;
  const double source = subject.clip != nullptr ? subject.clip->fps() : 0.0;
  ImGui::Spacing();
  ImGui::TextColored(kDimColor, "Frame rate");
  auto rate_button = [&](ExportRate rate, const char* label, const char* tip) {
    if (ImGui::RadioButton(label, settings_.rate == rate)) settings_.rate = rate;
    tooltip(tip);
  };
  char source_label[48];
  const char* letter = take_letter(0, subject.takes);
  std::snprintf(source_label, sizeof source_label, "%s own (%g)", *letter ? "A's" : "The reference's", source);
  const std::string source_tip = "The rate of " + (subject.name.empty() ? std::string("the reference take") : subject.name);
  rate_button(ExportRate::kSource, source_label, source_tip.c_str());
  ImGui::SameLine();
  rate_button(ExportRate::k30, "30", working == 30.0 ? "30 frames per second: the result's own frames" : "30 frames per second");
  ImGui::SameLine();
  rate_button(ExportRate::k60, "60", "60 frames per second (frames in between are interpolated)");
  ImGui::SameLine();
  rate_button(ExportRate::k120, "120", "120 frames per second (frames in between are interpolated)");
  ImGui::SameLine();
  rate_button(ExportRate::kCustom, "Other", "Any rate above 0 and up to 1000 frames per second");
  if (settings_.rate == ExportRate::kCustom) {
    ImGui::SameLine();
    ImGui::SetNextItemWidth(kFieldWidth * 0.7f);
    ImGui::InputDouble("fps", &settings_.custom_fps, 0.0, 0.0, "%.6g");
    tooltip("Frames per second of the file");
  }
}

void ExportDialog::draw_range(const EditorState& state, const ExportSubject& subject) {
  const double length = motion_length_s(subject.frames, subject.working_fps);
  ImGui::Spacing();
  ImGui::TextColored(kDimColor, "Frames");
  char all_label[64];
  std::snprintf(all_label, sizeof all_label, "All (%s)", duration_in_words(length).c_str());
  if (ImGui::RadioButton(all_label, settings_.range == ExportRange::kAll)) settings_.range = ExportRange::kAll;
  tooltip("The whole result, first frame to last");
  ImGui::SameLine();
  if (ImGui::RadioButton("In to out", settings_.range == ExportRange::kInOut)) settings_.range = ExportRange::kInOut;
  tooltip("From the in point to the out point, both included");
  ImGui::SameLine();
  const int cycles = subject.loop_cycles;
  char loop_label[64];
  if (cycles > 0)
    std::snprintf(loop_label, sizeof loop_label, "The loop (%d cycle%s)", cycles, cycles == 1 ? "" : "s");
  else
    std::snprintf(loop_label, sizeof loop_label, "The loop");
  ImGui::BeginDisabled(cycles <= 0);
  if (ImGui::RadioButton(loop_label, settings_.range == ExportRange::kLoop)) settings_.range = ExportRange::kLoop;
  ImGui::EndDisabled();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip("%s", cycles > 0 ? "The result's seamless loop of whole gait cycles: the file repeats without a\n"
                                         "hitch, at any frame rate"
                                       : "Turn on Loop in the parameters panel to cut a seamless loop of the result");
  if (settings_.range == ExportRange::kInOut) {
    draw_in_out_fields(subject);
    draw_in_out_buttons(state, subject);
  }
}

void ExportDialog::draw_in_out_fields(const ExportSubject& subject) {
  const double working = subject.working_fps;
  const int blend_frames = subject.frames;
  const double length = motion_length_s(blend_frames, working);
  double in = settings_.in_s, out = settings_.out_s;
  bool in_done = false, out_done = false, typing = false;
  if (settings_.range_in_frames) {
    int in_f = static_cast<int>(std::lround(in * working));
    int out_f = static_cast<int>(std::lround(out * working));
    const int last = std::max(blend_frames - 1, 0);
    ImGui::SetNextItemWidth(kFieldWidth);
    if (ImGui::InputInt("In##frames", &in_f, 0, 0)) in = std::clamp(in_f, 0, last) / working;
    in_done = ImGui::IsItemDeactivatedAfterEdit();
    typing |= ImGui::IsItemActive();
    tooltip("The first frame written, a frame of the result as the playback bar counts them: click and type it");
    ImGui::SameLine();
    ImGui::SetNextItemWidth(kFieldWidth);
    if (ImGui::InputInt("Out##frames", &out_f, 0, 0)) out = std::clamp(out_f, 0, last) / working;
    out_done = ImGui::IsItemDeactivatedAfterEdit();
    typing |= ImGui::IsItemActive();
    tooltip("The last frame written: click and type it");
  } else {
    ImGui::SetNextItemWidth(kFieldWidth);
    if (ImGui::InputDouble("In (s)##s", &in, 0.0, 0.0, "%.3f")) in = std::clamp(in, 0.0, length);
    in_done = ImGui::IsItemDeactivatedAfterEdit();
    typing |= ImGui::IsItemActive();
    tooltip("Where the file starts, seconds from the result's first frame: click and type it");
    ImGui::SameLine();
    ImGui::SetNextItemWidth(kFieldWidth);
    if (ImGui::InputDouble("Out (s)##s", &out, 0.0, 0.0, "%.3f")) out = std::clamp(out, 0.0, length);
    out_done = ImGui::IsItemDeactivatedAfterEdit();
    typing |= ImGui::IsItemActive();
    tooltip("Where the file ends (that frame included): click and type it");
  }
  // A point typed past the other takes it along, once typed.
  settings_.in_s = in;
  settings_.out_s = out;
  if (in_done) settings_.out_s = std::max(settings_.out_s, settings_.in_s);
  if (out_done) settings_.in_s = std::min(settings_.in_s, settings_.out_s);
  typing_range_ = typing;
}

void ExportDialog::draw_in_out_buttons(const EditorState& state, const ExportSubject& subject) {
  const double working = subject.working_fps;
  const double length = motion_length_s(subject.frames, working);
  const ShownMotion* reference = state.reference_take();
  const double playhead = reference != nullptr ? frame_at(*reference, state.playback.time_s) / working : 0.0;
  if (ImGui::SmallButton("In at playhead")) {
    settings_.in_s = std::min(playhead, length);
    settings_.out_s = std::max(settings_.out_s, settings_.in_s);
  }
  tooltip("The in point at the frame the playback shows");
  ImGui::SameLine();
  if (ImGui::SmallButton("Out at playhead")) {
    settings_.out_s = std::min(playhead, length);
    settings_.in_s = std::min(settings_.in_s, settings_.out_s);
  }
  tooltip("The out point at the frame the playback shows");
  ImGui::SameLine();
  ImGui::Checkbox("in frames", &settings_.range_in_frames);
  tooltip("Count the in and out points in the result's frames; off: in seconds");
}

void ExportDialog::draw_channels(const ExportSubject& subject, ExportFormat format) {
  // The channels (BVH; glTF and FBX key translations where joints travel, rotations everywhere).
  ImGui::Spacing();
  ImGui::BeginDisabled(format != ExportFormat::kBvh);
  ImGui::TextColored(kDimColor, "Channels");
  const std::string as_source = "As " + (subject.name.empty() ? std::string("the reference take's file") : subject.name);
  const char* layout_names[2] = {"Rotations (positions on the root only)", as_source.c_str()};
  const int current = settings_.layout == ChannelLayout::kRotations ? 0 : 1;
  ImGui::SetNextItemWidth(kWrapWidth - 60.0f);
  if (ImGui::BeginCombo("##layout", layout_names[current])) {
    for (int i = 0; i < 2; ++i) {
      if (ImGui::Selectable(layout_names[i], i == current))
        settings_.layout = i == 0 ? ChannelLayout::kRotations : ChannelLayout::kAsSource;
      if (i == 0)
        tooltip("Position channels only where the body travels, so Blender, three.js and game engines\n"
                "all place the joints alike (a joint's constant positions go into its offset)");
      else
        tooltip("The channels of the reference take's file, joint by joint (needed when its bones change length)");
    }
    ImGui::EndCombo();
  }
  tooltip("How the file's channels are laid out; the default is what suits the reference take");
  ImGui::EndDisabled();
}

void ExportDialog::draw_summary(const ExportSubject& subject) {
  // What will be written.
  const double working = subject.working_fps;
  const int blend_frames = subject.frames;
  const double length = motion_length_s(blend_frames, working);
  const ExportOptions o = options();
  const bool rate_ok = std::isfinite(o.fps) && o.fps > 0.0 && o.fps <= kMaxExportFps;
  if (!rate_ok) {
    wrapped(kErrorColor, "The frame rate must be above 0 and at most 1000 frames per second.");
  } else if (subject.frames > 0) {
    int frames = 0;
    if (o.range == ExportRange::kLoop)
      frames = std::max(1, static_cast<int>(std::lround(blend_frames * o.fps / working)));
    else if (o.range == ExportRange::kInOut)
      frames = export_frame_count(o.in_s, o.out_s, o.fps);
    else
      frames = export_frame_count(0.0, length, o.fps);
    char summary[96];
    std::snprintf(summary, sizeof summary, "Writes %d frames at %g fps.", frames, o.fps);
    ImGui::TextColored(kDimColor, "%s", summary);
  }
}

void ExportDialog::draw_actions(bool busy, bool enter, bool* open) {
  // Export, the question before an overwrite, or the progress.
  ImGui::Separator();
  if (busy) {
    ImGui::ProgressBar(job_.progress(), ImVec2(kWrapWidth - 100.0f, 0.0f), "exporting");
    ImGui::SameLine();
    if (ImGui::Button("Cancel")) press_cancel();
    tooltip("Stop the export; a file already being written is finished");
  } else if (confirm_) {
    wrapped(kWarningColor, fs::path(confirm_path_).filename().string() + " exists. Overwrite it?");
    if (ImGui::Button("Overwrite")) press_overwrite();
    tooltip("Replace the file with the result");
    ImGui::SameLine();
    if (ImGui::Button("Keep it")) press_cancel();
    tooltip("Do not write; choose another file name");
  } else {
    if (ImGui::Button("Export") || enter) press_export();
    tooltip("Write the result on the reference take's skeleton (BVH, glTF or FBX, by the file's extension), in\n"
            "the background");
    ImGui::SameLine();
    if (ImGui::Button("Close")) *open = false;
  }
}

void ExportDialog::draw_status() {
  if (status_.message.empty()) return;
  wrapped(status_.ok ? kOkColor : kErrorColor, status_.message);  // the full path: where it went
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", status_.message.c_str());
}

}  // namespace mostyle::ui
