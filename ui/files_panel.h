#pragma once
// Paths for A and B with Load (Enter in a field loads too), a small browser of motion files (BVH,
// FBX, glTF; a file with several animations lists them, read on a thread when its row is opened,
// each loadable as FILE#ANIMATION), recent files,
// dropped files, load errors, and the export of the blend as BVH: the export field and button
// open the export dialog (ui/export_dialog.h), which this panel owns and draws. Files show by
// name; their folder is in the tooltip, never in the panel's text.
#include <future>
#include <map>
#include <string>
#include <vector>

#include "engine/io/scene_animation.h"

#include "ui/blend_session.h"
#include "ui/export_dialog.h"
#include "ui/panel.h"

namespace mostyle::ui {

// A path field that shows a file's name and keeps its folder aside (shown on hover). Text typed
// with a folder in it ("a/b.bvh", "/x/y.bvh") is taken as it is; a bare name is in `folder`.
struct PathField {
  char text[512] = "";
  std::string folder;

  void set(const std::string& path);  // name into text, the rest into folder
  std::string path() const;           // what to load; "" when the field is empty
};

// `text` with each of `folders` (and the slash after it) taken out, longest first: error and
// export sentences name files without their folders ("/data/walk.bvh:3: ..." -> "walk.bvh:3: ...").
std::string without_folders(std::string text, std::vector<std::string> folders);

class FilesPanel : public Panel {
 public:
  FilesPanel(BlendSession& session, std::string folder);
  void draw(EditorState& state) override;
  ExportDialog& export_dialog() { return export_dialog_; }

 private:
  BlendSession& session_;
  std::string folder_;  // the browser's folder
  PathField a_, b_;
  ExportDialog export_dialog_;  // its file is the export field's (settings().path)
  std::string synced_a_, synced_b_;  // the requested paths the fields were last filled from
  // The browser's listing of folder_, read when the folder changes or on Refresh (not per frame).
  std::string listed_folder_;
  std::vector<std::string> dirs_, files_;
  std::string list_error_;
  // The animations of the FBX and glTF files whose rows were opened, by path: read on a thread
  // (engine/io/motion_file.h read_motion_takes), polled each frame.
  struct FileTakes {
    std::future<std::vector<TakeInfo>> pending;
    std::vector<TakeInfo> takes;
    std::string error;
  };
  std::map<std::string, FileTakes> takes_;
};

}  // namespace mostyle::ui
