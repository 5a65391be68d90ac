#include "ui/files_panel.h"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <system_error>
#include <vector>

#include <imgui.h>

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

bool is_bvh(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  return ext == ".bvh";
}
}  // namespace

FilesPanel::FilesPanel(BlendSession& session, std::string folder) : session_(session), folder_(std::move(folder)) {}

void FilesPanel::draw(EditorState& state) {
  BlendSession& s = session_;
  // The fields follow the pair last asked for (not while the animator types): after a failed
  // load they hold the bad path, to correct.
  const WorkerSnapshot& snap = s.snapshot();
  if (s.requested_a() != synced_a_ || s.requested_b() != synced_b_) {
    synced_a_ = s.requested_a();
    synced_b_ = s.requested_b();
    copy_to(path_a_, sizeof path_a_, synced_a_);
    copy_to(path_b_, sizeof path_b_, synced_b_);
  }

  // Dropped files: two replace the pair, one replaces B (the style blended in).
  if (!s.dropped().empty()) {
    std::vector<std::string> files;
    files.swap(s.dropped());
    if (files.size() >= 2) {
      copy_to(path_a_, sizeof path_a_, files[0]);
      copy_to(path_b_, sizeof path_b_, files[1]);
    } else {
      copy_to(path_b_, sizeof path_b_, files[0]);
    }
    s.load(path_a_, path_b_);
  }
  place_next_window(Column::kLeft, 0.68f, 0.32f);
  if (!ImGui::Begin("Files")) {
    ImGui::End();
    return;
  }
  if (!s.error().empty()) {
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextColored(kErrorColor, "%s", s.error().c_str());
    ImGui::PopTextWrapPos();
  }
  ImGui::PushItemWidth(-92.0f);
  ImGui::InputText("##a", path_a_, sizeof path_a_);
  ImGui::SameLine();
  ImGui::TextColored(ImVec4(0.96f, 0.60f, 0.28f, 1.0f), "A");
  ImGui::SameLine();
  if (ImGui::Button("Load##a")) s.load(path_a_, snap.path_b.empty() ? path_b_ : snap.path_b);
  ImGui::InputText("##b", path_b_, sizeof path_b_);
  ImGui::SameLine();
  ImGui::TextColored(ImVec4(0.36f, 0.64f, 0.97f, 1.0f), "B");
  ImGui::SameLine();
  if (ImGui::Button("Load##b")) s.load(snap.path_a.empty() ? path_a_ : snap.path_a, path_b_);
  ImGui::PopItemWidth();
  if (ImGui::Button("Load pair")) s.load(path_a_, path_b_);
  ImGui::SameLine();
  ImGui::TextColored(kDimColor, "or drop .bvh files here");
  ImGui::SetNextItemWidth(-92.0f);
  ImGui::InputText("##export", export_path_, sizeof export_path_);
  ImGui::SameLine();
  if (ImGui::Button("Export BVH")) s.export_bvh(export_path_);
  if (!s.export_message().empty()) {
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextColored(s.export_ok() ? kOkColor : kErrorColor, "%s", s.export_message().c_str());
    ImGui::PopTextWrapPos();
  }

  if (ImGui::CollapsingHeader("Browse", ImGuiTreeNodeFlags_DefaultOpen)) {
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextColored(kDimColor, "%s", folder_.c_str());
    ImGui::PopTextWrapPos();
    if (ImGui::SmallButton("Refresh")) listed_folder_.clear();
    if (listed_folder_ != folder_) {
      listed_folder_ = folder_;
      dirs_.clear();
      files_.clear();
      list_error_.clear();
      std::error_code ec;
      for (fs::directory_iterator it(folder_, ec), end; !ec && it != end; it.increment(ec)) {
        std::error_code e2;
        if (it->is_directory(e2)) {
          if (it->path().filename().string().rfind('.', 0) != 0) dirs_.push_back(it->path().string());
        } else if (is_bvh(it->path())) {
          files_.push_back(it->path().string());
        }
      }
      if (ec) list_error_ = folder_ + ": " + ec.message();
      std::sort(dirs_.begin(), dirs_.end());
      std::sort(files_.begin(), files_.end());
    }
    if (!list_error_.empty()) ImGui::TextColored(kErrorColor, "%s", list_error_.c_str());
    ImGui::BeginChild("##browser", ImVec2(0.0f, ImGui::GetTextLineHeightWithSpacing() * 5.0f), true);
    if (ImGui::Selectable("..")) {
      fs::path up = fs::absolute(folder_).lexically_normal();
      if (!up.has_filename()) up = up.parent_path();  // "a/b/" -> "a/b"
      folder_ = up.parent_path().string();
    }
    std::string next_folder;
    for (const std::string& d : dirs_)
      if (ImGui::Selectable((fs::path(d).filename().string() + "/").c_str())) next_folder = d;
    for (const std::string& name : files_) {
      const fs::path f(name);
      ImGui::PushID(f.string().c_str());
      if (ImGui::SmallButton("A")) s.load(f.string(), snap.path_b.empty() ? f.string() : snap.path_b);
      ImGui::SameLine();
      if (ImGui::SmallButton("B")) s.load(snap.path_a.empty() ? f.string() : snap.path_a, f.string());
      ImGui::SameLine();
      ImGui::TextUnformatted(f.filename().string().c_str());
      ImGui::PopID();
    }
    if (dirs_.empty() && files_.empty()) ImGui::TextColored(kDimColor, "no .bvh files here");
    ImGui::EndChild();
    if (!next_folder.empty()) folder_ = next_folder;
  }
  if (ImGui::CollapsingHeader("Recent")) {
    for (const std::string& r : s.recent()) {
      ImGui::PushID(r.c_str());
      if (ImGui::SmallButton("A")) copy_to(path_a_, sizeof path_a_, r);
      ImGui::SameLine();
      if (ImGui::SmallButton("B")) copy_to(path_b_, sizeof path_b_, r);
      ImGui::SameLine();
      ImGui::TextUnformatted(fs::path(r).filename().string().c_str());
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", r.c_str());
      ImGui::PopID();
    }
  }
  (void)state;
  ImGui::End();
}

}  // namespace mostyle::ui
