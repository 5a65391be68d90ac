#include "ui/panels/files_panel.h"
#include "ui/panels/theme.h"

#include <algorithm>
#include <cfloat>
#include <cstring>
#include <filesystem>
#include <system_error>
#include <vector>

#include <imgui.h>
#include <imgui_internal.h>  // PushOverrideID: the panel's items keep their ids inside its body

#include <chrono>

#include "engine/io/motion_file.h"
#include "engine/base/numbers.h"

#include "ui/panels/layout.h"
#include "ui/model/live_style_spec.h"
#include "ui/model/result_view.h"

namespace mostyle::ui {
namespace fs = std::filesystem;
namespace {

void copy_to(char* field, size_t size, const std::string& text) {
  std::strncpy(field, text.c_str(), size - 1);
  field[size - 1] = '\0';
}

bool is_motion(const fs::path& p) { return is_motion_file(p.string()); }

// A folder's own name with a slash ("motions/"), for the panel's text; "/" and "." as they are.
std::string folder_name(const std::string& folder) {
  fs::path p(folder);
  if (!p.has_filename() && p.has_parent_path() && p.parent_path() != p) p = p.parent_path();  // "a/b/" -> "a/b"
  const std::string name = p.filename().string();
  return name.empty() || name == "." || name == ".." ? folder : name + "/";
}

// A sentence that may name files, without their folders; the whole sentence on hover.
void sentence(const ImVec4& color, const std::string& text, const std::vector<std::string>& folders) {
  ImGui::PushTextWrapPos(0.0f);
  ImGui::TextColored(color, "%s", without_folders(text, folders).c_str());
  ImGui::PopTextWrapPos();
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", text.c_str());
}
}  // namespace

void PathField::set(const std::string& path) {
  const fs::path p(path);
  if (p.has_filename() && p.has_parent_path()) {
    folder = p.parent_path().string();
    copy_to(text, sizeof text, p.filename().string());
  } else {
    folder.clear();
    copy_to(text, sizeof text, path);
  }
}

std::string PathField::path() const {
  const fs::path t(text);
  if (t.empty()) return std::string();
  if (t.has_parent_path() || folder.empty()) return t.string();
  return (fs::path(folder) / t).string();
}

std::string without_folders(std::string text, std::vector<std::string> folders) {
  // Longest first: "/data/" must not eat the start of "/data/walks/".
  std::sort(folders.begin(), folders.end(),
            [](const std::string& x, const std::string& y) { return x.size() > y.size(); });
  for (std::string f : folders) {
    if (f.empty() || f == "." || f == "/") continue;
    if (f.back() != '/') f += '/';
    for (size_t at = text.find(f); at != std::string::npos; at = text.find(f, at)) text.erase(at, f.size());
  }
  return text;
}

std::string take_role(int take, int takes) {
  const char* letter = take_letter(take, takes);
  return *letter ? letter : std::to_string(take + 1);
}

std::vector<std::string> with_take(std::vector<std::string> takes, size_t index, const std::string& path) {
  // An empty field last (a take alone with itself: the B it lacks) takes a file added.
  if (index == takes.size() && !takes.empty() && takes.back().empty()) index = takes.size() - 1;
  if (index >= takes.size()) takes.push_back(path);
  else takes[index] = path;
  return takes;
}

FilesPanel::FilesPanel(EngineLink& engine, std::string folder)
    : engine_(engine), folder_(std::move(folder)), export_dialog_(engine) {}

void FilesPanel::take_buttons(const std::string& path, const std::vector<std::string>& takes) {
  EngineLink& s = engine_;
  const int n = static_cast<int>(takes.size());
  if (ImGui::SmallButton("+")) s.load_files(with_take(takes, takes.size(), path));
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Add as one more take");
  ImGui::SameLine();
  if (ImGui::SmallButton("Replace...")) ImGui::OpenPopup("##replace");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Put this file in place of one of the takes");
  if (ImGui::BeginPopup("##replace")) {
    for (int i = 0; i < n; ++i) {
      const std::string label = take_role(i, n) + "  " + fs::path(takes[static_cast<size_t>(i)]).filename().string() +
                                (i == 0 ? "  (reference)" : "");
      if (ImGui::Selectable(label.c_str())) s.load_files(with_take(takes, static_cast<size_t>(i), path));
    }
    ImGui::EndPopup();
  }
  ImGui::SameLine();
}

void FilesPanel::draw(EditorState& state) {
  export_dialog_.draw(state);  // its own window; polled even while hidden, so an outcome arrives
  sync_fields();
  const std::vector<std::string>& takes = synced_;
  load_dropped(state, takes);
  place_panel(PanelId::kFiles, state);
  if (!ImGui::Begin(panel_title(PanelId::kFiles))) {
    ImGui::End();
    return;
  }
  // Folders left out of the panel's sentences (shown whole on hover).
  std::error_code ec;
  const fs::path export_path(export_dialog_.settings().path);
  const std::string export_folder = export_path.is_relative() && !state.files_folder.empty()
                                        ? (fs::path(state.files_folder) / export_path).parent_path().string()
                                        : fs::absolute(export_path, ec).parent_path().string();
  std::vector<std::string> folders = {folder_, export_folder};
  for (const PathField& f : fields_) folders.push_back(f.folder);

  // The Live section sits at the panel's foot, so that it shows at any window size and for any
  // number of takes; the rest scrolls above it, in what the Live section leaves (as much as it
  // needs when open, as measured on the frame before; all of it, scrolling, when that is more).
  const float spacing = ImGui::GetStyle().ItemSpacing.y;
  const float avail = ImGui::GetContentRegionAvail().y;
  const float foot = std::min(live_height_, avail);
  const float body = avail - foot - spacing;
  if (body >= ImGui::GetFrameHeight()) {
    const ImGuiID panel_id = ImGui::GetCurrentWindow()->ID;
    ImGui::BeginChild("##files-body", ImVec2(0.0f, body), false);
    ImGui::PushOverrideID(panel_id);  // the fields' and buttons' ids are the panel's, as without a body
    draw_take_fields(takes);
    draw_messages();
    draw_browser(takes);
    draw_recent(state, takes);
    ImGui::PopID();
    ImGui::EndChild();
  }
  {  // The export field and the Live section: at the foot, in view at any window size.
    const bool fits = live_height_ <= avail;
    const ImGuiID panel_id = ImGui::GetCurrentWindow()->ID;
    ImGui::BeginChild("##live", ImVec2(0.0f, foot), false, fits ? ImGuiWindowFlags_NoScrollbar : 0);
    ImGui::PushOverrideID(panel_id);  // the export field's id is the panel's, wherever it is drawn
    draw_export_field(state, export_folder);
    ImGui::PopID();
    if (live_ != nullptr) draw_live(state);
    live_height_ = std::max(ImGui::GetFrameHeight(), ImGui::GetCursorPosY() - spacing);
    ImGui::EndChild();
  }
  ImGui::End();
}

void FilesPanel::sync_fields() {
  // The fields follow the takes last asked for (not while the animator types): after a failed
  // load they hold the bad path, to correct.
  std::vector<std::string> requested = engine_.requested_files();
  if (requested.size() < 2) requested.resize(2);  // a pair's B field, empty: A with itself
  if (requested != synced_) {
    synced_ = requested;
    fields_.assign(requested.size(), PathField());
    for (size_t i = 0; i < requested.size(); ++i) fields_[i].set(requested[i]);
  }
}

void FilesPanel::load_dropped(EditorState& state, const std::vector<std::string>& takes) {
  // Dropped files: two or more are the new takes (the first the reference); one is one more take
  // (the B a take alone with itself lacked).
  if (state.dropped.empty()) return;
  std::vector<std::string> files;
  files.swap(state.dropped);
  if (files.size() >= 2) engine_.load_files(files);
  else engine_.load_files(with_take(takes, takes.size(), files[0]));
}

void FilesPanel::draw_take_fields(const std::vector<std::string>& takes) {
  EngineLink& s = engine_;
  const int n = static_cast<int>(takes.size());
  // One path field per take: the file's name; on hover, its folder and what typing does. Enter
  // or Load loads the takes with this one as typed.
  std::vector<std::string> typed;
  for (const PathField& f : fields_) typed.push_back(f.path());
  ImGui::PushItemWidth(-116.0f);
  int remove = -1;
  for (int i = 0; i < n; ++i) {
    PathField& field = fields_[static_cast<size_t>(i)];
    ImGui::PushID(i);
    const glm::vec3 c = take_color(i);
    ImGui::TextColored(ImVec4(c.x, c.y, c.z, 1.0f), "%s", take_role(i, n).c_str());
    // The field 1.6 font sizes from the panel's edge (the body it is in starts at the panel's padding).
    ImGui::SameLine(ImGui::GetFontSize() * 1.6f - ImGui::GetStyle().WindowPadding.x);
    const bool entered = ImGui::InputText("##take", field.text, sizeof field.text, ImGuiInputTextFlags_EnterReturnsTrue);
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("Folder: %s\nType a file name in that folder, or a path; Enter loads it.",
                        field.folder.empty() ? "(where mostyle was started)" : field.folder.c_str());
    ImGui::SameLine();
    if (ImGui::Button("Load") || entered) s.load_files(with_take(takes, static_cast<size_t>(i), field.path()));
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("%s", i == 0 ? "Load this file as the reference (its skeleton, timing and path lead)"
                                     : "Load this file as this take");
    ImGui::SameLine();
    if (ImGui::SmallButton("x")) remove = i;
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("ShownMotion this take out (one left: the take with itself)");
    ImGui::PopID();
  }
  ImGui::PopItemWidth();
  if (remove >= 0) {
    std::vector<std::string> rest = takes;
    rest.erase(rest.begin() + remove);
    s.load_files(rest);
  }
  if (ImGui::Button("Load all")) s.load_files(typed);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Load every field as typed, as the new takes");
  ImGui::SameLine();
  ImGui::TextColored(kDimColor, "or drop motion files here");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Two or more files (BVH, FBX, glTF): the new takes. One file: one more take.");
}

void FilesPanel::draw_export_field(EditorState& state, const std::string& export_folder) {
  char* export_path = export_dialog_.settings().path;
  ImGui::SetNextItemWidth(-92.0f);
  const bool enter_export = ImGui::InputText("##export", export_path, sizeof export_dialog_.settings().path,
                                            ImGuiInputTextFlags_EnterReturnsTrue);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("File to export the result to (a name: in %s); Enter opens the export dialog.",
                      export_folder.c_str());
  ImGui::SameLine();
  if (ImGui::Button("Export...") || enter_export) command_open_export(state);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Choose the frame rate, the frames and the channels, then write the result on the\n"
                      "reference take's skeleton as BVH or glTF (.glb), by the file's extension (Ctrl+E)");
}

void FilesPanel::draw_messages() {
  // Messages in a space of their own that is always there: a load error (with the folder it
  // tried), the export's progress or outcome. Hover shows a message whole.
  ImGui::BeginChild("##messages", ImVec2(0.0f, ImGui::GetTextLineHeightWithSpacing() * 2.2f), false,
                    ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoScrollWithMouse);
  if (!engine_.error().empty()) sentence(kErrorColor, engine_.error(), {});
  if (export_dialog_.job().running())
    ImGui::ProgressBar(export_dialog_.job().progress(), ImVec2(-FLT_MIN, 0.0f), "exporting");
  else if (!export_dialog_.status().message.empty())
    sentence(export_dialog_.status().ok ? kOkColor : kErrorColor, export_dialog_.status().message, {});  // where, whole
  ImGui::EndChild();
}

void FilesPanel::draw_browser(const std::vector<std::string>& takes) {
  const bool browse = ImGui::CollapsingHeader("Browse", ImGuiTreeNodeFlags_DefaultOpen);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("The motion files of a folder (BVH, FBX, glTF), to load as a take or add to the takes;\n"
                      "open a file with animations to pick one");
  if (!browse) return;
  ImGui::TextColored(kDimColor, "in %s", folder_name(folder_).c_str());
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Folder: %s", folder_.c_str());
  ImGui::SameLine();
  if (ImGui::SmallButton("Refresh")) listed_folder_.clear();
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Read the folder again");
  if (listed_folder_ != folder_) list_folder();
  if (!list_error_.empty()) sentence(kErrorColor, list_error_, {});
  ImGui::BeginChild("##browser", ImVec2(0.0f, ImGui::GetTextLineHeightWithSpacing() * 5.0f), true);
  if (ImGui::Selectable("..")) {
    fs::path up = fs::absolute(folder_).lexically_normal();
    if (!up.has_filename()) up = up.parent_path();  // "a/b/" -> "a/b"
    folder_ = up.parent_path().string();
  }
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Up to the folder above");
  std::string next_folder;
  for (const std::string& d : dirs_) {
    if (ImGui::Selectable((fs::path(d).filename().string() + "/").c_str())) next_folder = d;
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Open this folder");
  }
  for (const std::string& name : files_) {
    const fs::path f(name);
    if (has_takes(motion_format(name))) draw_file_with_takes(name, takes);
    else take_row(f.string(), f.filename().string(), takes);
  }
  if (dirs_.empty() && files_.empty()) ImGui::TextColored(kDimColor, "no motion files here");
  ImGui::EndChild();
  if (!next_folder.empty()) folder_ = next_folder;
}

void FilesPanel::list_folder() {
  listed_folder_ = folder_;
  takes_.clear();  // a pending read finishes in its future's destructor
  dirs_.clear();
  files_.clear();
  list_error_.clear();
  std::error_code list_ec;
  for (fs::directory_iterator it(folder_, list_ec), end; !list_ec && it != end; it.increment(list_ec)) {
    std::error_code e2;
    if (it->is_directory(e2)) {
      if (it->path().filename().string().rfind('.', 0) != 0) dirs_.push_back(it->path().string());
    } else if (is_motion(it->path())) {
      files_.push_back(it->path().string());
    }
  }
  if (list_ec) list_error_ = "Cannot read " + folder_name(folder_) + ": " + list_ec.message();
  std::sort(dirs_.begin(), dirs_.end());
  std::sort(files_.begin(), files_.end());
}

void FilesPanel::take_row(const std::string& path, const std::string& label, const std::vector<std::string>& takes) {
  ImGui::PushID(path.c_str());
  take_buttons(path, takes);
  ImGui::TextUnformatted(label.c_str());
  ImGui::PopID();
}

void FilesPanel::draw_file_with_takes(const std::string& name, const std::vector<std::string>& takes) {
  // FBX and glTF: the file's row opens to its animations, read on a thread the first time.
  ImGui::PushID(name.c_str());
  const bool open = ImGui::TreeNode("##takes", "%s", fs::path(name).filename().string().c_str());
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Open to list the file's animations");
  if (open) {
    FileTakes& t = takes_[name];
    if (!t.pending.valid() && t.takes.empty() && t.error.empty()) {
      t.pending = std::async(std::launch::async, [name] { return read_motion_takes(name); });
    }
    if (t.pending.valid() && t.pending.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
      try {
        t.takes = t.pending.get();
      } catch (const std::exception& e) {
        t.error = e.what();
      }
    }
    if (t.pending.valid()) ImGui::TextColored(kDimColor, "reading...");
    if (!t.error.empty()) sentence(kErrorColor, t.error, {folder_});
    for (const TakeInfo& take : t.takes) {
      char label[320];
      std::snprintf(label, sizeof label, "%s (%s)", take.name.c_str(), duration_in_words(take.seconds).c_str());
      take_row(join_take_path(name, take.name), label, takes);
    }
    ImGui::TreePop();
  }
  ImGui::PopID();
}

void FilesPanel::draw_recent(const EditorState& state, const std::vector<std::string>& takes) {
  const bool recent = ImGui::CollapsingHeader("Recent");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Files loaded before, newest first");
  if (!recent) return;
  for (const std::string& r : state.recent.takes) {
    ImGui::PushID(r.c_str());
    take_buttons(r, takes);
    ImGui::TextUnformatted(fs::path(r).filename().string().c_str());
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Folder: %s", fs::path(r).parent_path().string().c_str());
    ImGui::PopID();
  }
}

void FilesPanel::sync_live_fields() {
  const LiveSettings& l = live_->settings();
  if (live_fields_filled_ && l.address == live_synced_.address && l.skeleton == live_synced_.skeleton &&
      l.record_path == live_synced_.record_path)
    return;
  live_synced_ = l;
  live_fields_filled_ = true;
  copy_to(live_address_, sizeof live_address_, l.address);
  copy_to(live_skeleton_, sizeof live_skeleton_, l.skeleton);
  copy_to(live_record_, sizeof live_record_, l.record_path);
}

void FilesPanel::draw_live(const EditorState& state) {
  if (live_ == nullptr) return;
  // Open from the start when the editor connects by itself (--live).
  if (live_->status().state != LiveState::kOff) ImGui::SetNextItemOpen(true, ImGuiCond_Once);
  const bool open = ImGui::CollapsingHeader("Live");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Style a motion-capture stream as it comes (Axis Neuron's BVH broadcasting, string format,\n"
                      "TCP) with the loaded takes as the result shows them: the stream as the first take (a\n"
                      "transfer's content), every other take but the neutral a style at its weight; new takes\n"
                      "restyle it on the same connection");
  if (!open) return;
  sync_live_fields();
  LiveSettings& settings = live_->settings();
  const bool active = live_->active();
  ImGui::PushItemWidth(-92.0f);
  ImGui::InputText("##live-address", live_address_, sizeof live_address_);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("HOST:PORT of the stream's server (Axis Neuron's BVH port is 7001 by default)");
  ImGui::SameLine();
  if (ImGui::Button(active ? "Disconnect" : "Connect")) {
    live_error_.clear();
    if (active) {
      live_->disconnect();
    } else if (engine_.takes() == nullptr) {
      live_error_ = "Live: load two takes or more first: a neutral and the styles.";
    } else {
      settings.address = live_address_;
      settings.skeleton = live_skeleton_;
      live_synced_ = settings;
      try {
        live_->connect(settings, live_style_spec(*engine_.takes(), state.document));
      } catch (const std::exception& e) {
        live_error_ = e.what();
      }
    }
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(active ? "Stop styling the stream (a recording ends complete)"
                             : "Connect to the stream and style it with the loaded takes");
  ImGui::InputText("##live-skeleton", live_skeleton_, sizeof live_skeleton_);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("A BVH file with the stream's hierarchy and channels (exported from Axis with the same\n"
                      "output settings); its frames are ignored, its Frame Time is the stream's rate");
  ImGui::SameLine();
  ImGui::TextColored(kDimColor, "skeleton");
  ImGui::PopItemWidth();
  draw_live_status();
  draw_live_recording();
}

void FilesPanel::draw_live_status() {
  const LiveStatus& s = live_->status();
  const bool failed = !live_error_.empty() || s.state == LiveState::kFailed;
  const ImVec4 color = failed ? kErrorColor : s.state == LiveState::kStreaming ? kOkColor : kDimColor;
  sentence(color, live_error_.empty() ? live_status_line(s) : live_error_, {});
  if (!s.last_skip.empty() && ImGui::IsItemHovered()) ImGui::SetTooltip("last skipped: %s", s.last_skip.c_str());
  if (!s.strength_error.empty()) sentence(kErrorColor, s.strength_error, {});
  if (!s.restyle_error.empty()) sentence(kErrorColor, s.restyle_error, {});
}

void FilesPanel::draw_live_recording() {
  const LiveStatus& s = live_->status();
  LiveSettings& settings = live_->settings();
  ImGui::SetNextItemWidth(-122.0f);
  ImGui::InputText("##live-record", live_record_, sizeof live_record_);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("The BVH file the styled stream is recorded to: it reads whole at every moment");
  ImGui::SameLine();
  if (ImGui::Button(s.recording ? "Stop recording" : "Record")) {
    if (s.recording) {
      live_->stop_recording();
    } else {
      settings.record_path = live_record_;
      live_synced_.record_path = settings.record_path;
      live_->start_recording(settings.record_path, settings.record_input);
    }
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(s.recording ? "End the recording: the file holds every frame so far"
                                  : "Record the styled stream from the next frame on");
  ImGui::Checkbox("record the stream as it came too", &settings.record_input);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Beside the styled recording, as NAME.input.bvh");
  if (s.recording) {
    ImGui::TextColored(kOkColor, "recording: %lld frames", s.recorded);
  } else if (!s.record_error.empty()) {
    sentence(kErrorColor, s.record_error, {});
  } else if (s.recorded > 0) {
    ImGui::TextColored(kDimColor, "recorded %lld frames to %s", s.recorded, fs::path(s.record_path).filename().string().c_str());
  }
}

}  // namespace mostyle::ui
