#include "ui/files_panel.h"

#include <algorithm>
#include <cfloat>
#include <cstring>
#include <filesystem>
#include <system_error>
#include <vector>

#include <imgui.h>

#include <chrono>

#include "engine/io/motion_file.h"

#include "ui/layout.h"

namespace mostyle::ui {
namespace fs = std::filesystem;
namespace {
const ImVec4 kErrorColor(1.0f, 0.45f, 0.40f, 1.0f);
const ImVec4 kDimColor(0.60f, 0.62f, 0.66f, 1.0f);
const ImVec4 kOkColor(0.55f, 0.85f, 0.55f, 1.0f);

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

FilesPanel::FilesPanel(BlendSession& session, std::string folder)
    : session_(session), folder_(std::move(folder)), export_dialog_(session) {}

void FilesPanel::draw(EditorState& state) {
  BlendSession& s = session_;
  export_dialog_.draw(state);  // its own window; polled even while hidden, so an outcome arrives
  // The fields follow the pair last asked for (not while the animator types): after a failed
  // load they hold the bad path, to correct.
  const WorkerSnapshot& snap = s.snapshot();
  if (s.requested_a() != synced_a_ || s.requested_b() != synced_b_) {
    synced_a_ = s.requested_a();
    synced_b_ = s.requested_b();
    a_.set(synced_a_);
    b_.set(synced_b_);
  }

  // Dropped files: three or more open the style palette (the first the reference), two replace
  // the pair, one replaces B (the style blended in).
  if (!s.dropped().empty()) {
    std::vector<std::string> files;
    files.swap(s.dropped());
    if (files.size() >= 3) {
      s.load_files(files);
    } else {
      if (files.size() >= 2) {
        a_.set(files[0]);
        b_.set(files[1]);
      } else {
        b_.set(files[0]);
      }
      s.load(a_.path(), b_.path());
    }
  }
  place_panel(PanelId::kFiles, state);
  if (!ImGui::Begin(panel_title(PanelId::kFiles))) {
    ImGui::End();
    return;
  }
  // Folders left out of the panel's sentences (shown whole on hover).
  std::error_code ec;
  char* export_path = export_dialog_.settings().path;
  const std::string export_folder = fs::absolute(fs::path(export_path), ec).parent_path().string();
  const std::vector<std::string> folders = {a_.folder, b_.folder, folder_, export_folder,
                                            fs::path(snap.path_a).parent_path().string(),
                                            fs::path(snap.path_b).parent_path().string()};
  if (!s.error().empty()) sentence(kErrorColor, s.error(), folders);

  // A path field: the file's name; on hover, its folder and what typing does. Enter loads.
  auto path_field = [&](const char* id, PathField& field) {
    const bool entered = ImGui::InputText(id, field.text, sizeof field.text, ImGuiInputTextFlags_EnterReturnsTrue);
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("Folder: %s\nType a file name in that folder, or a path; Enter loads it.",
                        field.folder.empty() ? "(where mostyle was started)" : field.folder.c_str());
    return entered;
  };
  ImGui::PushItemWidth(-92.0f);
  const bool enter_a = path_field("##a", a_);
  ImGui::SameLine();
  ImGui::TextColored(ImVec4(0.96f, 0.60f, 0.28f, 1.0f), "A");
  ImGui::SameLine();
  if (ImGui::Button("Load##a") || enter_a) s.load(a_.path(), snap.path_b.empty() ? b_.path() : snap.path_b);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Load this file as A, the take whose timing and skeleton lead");
  const bool enter_b = path_field("##b", b_);
  ImGui::SameLine();
  ImGui::TextColored(ImVec4(0.36f, 0.64f, 0.97f, 1.0f), "B");
  ImGui::SameLine();
  if (ImGui::Button("Load##b") || enter_b) s.load(snap.path_a.empty() ? a_.path() : snap.path_a, b_.path());
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Load this file as B, the style blended in");
  ImGui::PopItemWidth();
  if (ImGui::Button("Load pair")) s.load(a_.path(), b_.path());
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Load both fields as the new pair");
  ImGui::SameLine();
  ImGui::TextColored(kDimColor, "or drop motion files here");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Two files: the new pair. One file: the new B.");
  ImGui::SetNextItemWidth(-92.0f);
  const bool enter_export = ImGui::InputText("##export", export_path, sizeof export_dialog_.settings().path,
                                            ImGuiInputTextFlags_EnterReturnsTrue);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("File to export the blend to (a name: in %s); Enter opens the export dialog.",
                      export_folder.c_str());
  ImGui::SameLine();
  if (ImGui::Button("Export...") || enter_export) command_open_export(state);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Choose the frame rate, the frames and the channels, then write the blend\n"
                      "on A's skeleton as BVH or glTF (.glb), by the file's extension (Ctrl+E)");
  if (export_dialog_.job().running())
    ImGui::ProgressBar(export_dialog_.job().progress(), ImVec2(-FLT_MIN, 0.0f), "exporting");
  else if (!s.export_message().empty())
    sentence(s.export_ok() ? kOkColor : kErrorColor, s.export_message(), folders);

  const bool browse = ImGui::CollapsingHeader("Browse", ImGuiTreeNodeFlags_DefaultOpen);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("The motion files of a folder (BVH, FBX, glTF), to load as A or B;\nopen a file with animations to pick one");
  if (browse) {
    ImGui::TextColored(kDimColor, "in %s", folder_name(folder_).c_str());
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Folder: %s", folder_.c_str());
    ImGui::SameLine();
    if (ImGui::SmallButton("Refresh")) listed_folder_.clear();
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Read the folder again");
    if (listed_folder_ != folder_) {
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
    // One row: A and B buttons and a label; `take` is "" for a whole file.
    auto take_row = [&](const std::string& path, const std::string& label) {
      ImGui::PushID(path.c_str());
      if (ImGui::SmallButton("A")) s.load(path, snap.path_b.empty() ? path : snap.path_b);
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("Load as A");
      ImGui::SameLine();
      if (ImGui::SmallButton("B")) s.load(snap.path_a.empty() ? path : snap.path_a, path);
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("Load as B");
      ImGui::SameLine();
      ImGui::TextUnformatted(label.c_str());
      ImGui::PopID();
    };
    for (const std::string& name : files_) {
      const fs::path f(name);
      if (!has_takes(motion_format(name))) {
        take_row(f.string(), f.filename().string());
        continue;
      }
      // FBX and glTF: the file's row opens to its animations, read on a thread the first time.
      ImGui::PushID(name.c_str());
      const bool open = ImGui::TreeNode("##takes", "%s", f.filename().string().c_str());
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
          std::snprintf(label, sizeof label, "%s (%.1f s)", take.name.c_str(), take.seconds);
          take_row(join_take_path(name, take.name), label);
        }
        ImGui::TreePop();
      }
      ImGui::PopID();
    }
    if (dirs_.empty() && files_.empty()) ImGui::TextColored(kDimColor, "no motion files here");
    ImGui::EndChild();
    if (!next_folder.empty()) folder_ = next_folder;
  }
  const bool recent = ImGui::CollapsingHeader("Recent");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Files loaded before, newest first");
  if (recent) {
    for (const std::string& r : s.recent()) {
      ImGui::PushID(r.c_str());
      if (ImGui::SmallButton("A")) a_.set(r);
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("Put in the A field (then Load or Enter)");
      ImGui::SameLine();
      if (ImGui::SmallButton("B")) b_.set(r);
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("Put in the B field (then Load or Enter)");
      ImGui::SameLine();
      ImGui::TextUnformatted(fs::path(r).filename().string().c_str());
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("Folder: %s", fs::path(r).parent_path().string().c_str());
      ImGui::PopID();
    }
  }
  ImGui::End();
}

}  // namespace mostyle::ui
