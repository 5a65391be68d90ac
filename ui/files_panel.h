#pragma once
// Paths for A and B with Load, a small .bvh browser, recent files, dropped files, load errors,
// and the export of the blend as BVH.
#include <string>
#include <vector>

#include "ui/blend_session.h"
#include "ui/panel.h"

namespace mostyle::ui {

class FilesPanel : public Panel {
 public:
  FilesPanel(BlendSession& session, std::string folder);
  void draw(EditorState& state) override;

 private:
  BlendSession& session_;
  std::string folder_;
  char path_a_[512] = "";
  char path_b_[512] = "";
  char export_path_[512] = "blend.bvh";
  std::string synced_a_, synced_b_;  // the requested paths the fields were last filled from
  // The browser's listing of folder_, read when the folder changes or on Refresh (not per frame).
  std::string listed_folder_;
  std::vector<std::string> dirs_, files_;
  std::string list_error_;
};

}  // namespace mostyle::ui
