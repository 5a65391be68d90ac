#pragma once
// The takes as one list of path fields, whatever their number (A and B for two, numbered for a
// palette), each with Load (Enter in a field loads too) and, in a palette, a remove button; a
// small browser of motion files (BVH, FBX, glTF; a file with several animations lists them, read
// on a thread when its row is opened, each loadable as FILE#ANIMATION) and the recent files,
// whose buttons replace a take or add one; dropped files; and the export of the result: the
// export field and button open the export dialog (ui/panels/export_dialog.h), which this panel owns and
// draws; and at the panel's foot, always in view, the Live section (a motion-capture stream styled
// with the takes). Files show by name, their folder on hover; a load error names the folder tried.
// Messages sit in a space of their own below the fields, so nothing moves under the mouse when
// one comes or goes.
#include <future>
#include <map>
#include <string>
#include <vector>

#include "engine/io/scene_animation.h"

#include "ui/model/engine_link.h"
#include "ui/model/live_source.h"
#include "ui/panels/export_dialog.h"
#include "ui/panels/panel.h"

namespace mostyle::ui {

// A path field that shows a file's name and keeps its folder aside (shown on hover). Text typed
// with a folder in it ("a/b.bvh", "/x/y.bvh") is taken as it is; a bare name is in `folder`.
struct PathField {
  char text[512] = "";
  std::string folder;

  void set(const std::string& path);  // name into text, the rest into folder
  std::string path() const;           // what to load; "" when the field is empty
};

// What a take is called in the panel: "A" and "B" in a pair (take_letter), "1" to "N" for more.
std::string take_role(int take, int takes);
// `takes` with take `index` replaced by `path` (index == size: `path` added, or put in an empty
// last field: A alone with itself gets its B).
std::vector<std::string> with_take(std::vector<std::string> takes, size_t index, const std::string& path);

// `text` with each of `folders` (and the slash after it) taken out, longest first: error and
// export sentences name files without their folders ("/data/walk.bvh:3: ..." -> "walk.bvh:3: ...").
std::string without_folders(std::string text, std::vector<std::string> folders);

class FilesPanel : public Panel {
 public:
  FilesPanel(EngineLink& engine, std::string folder);
  void draw(EditorState& state) override;
  ExportDialog& export_dialog() { return export_dialog_; }
  // The live source the Live section drives (the editor's); none: no Live section.
  void set_live(LiveSource* live) { live_ = live; }

 private:
  // The buttons that put `path` among `takes`: + (add) and Replace... (which take).
  void take_buttons(const std::string& path, const std::vector<std::string>& takes);
  // One row of the browser: the take buttons for `path`, then `label`.
  void take_row(const std::string& path, const std::string& label, const std::vector<std::string>& takes);

  // The steps of draw, in the order it takes them; `takes` are the takes last asked for (synced_).
  void sync_fields();  // the fields to the requested takes, when those changed
  void load_dropped(EditorState& state, const std::vector<std::string>& takes);
  void draw_take_fields(const std::vector<std::string>& takes);  // a field per take, Load all
  // The export field and Export... (opens the dialog).
  void draw_export_field(EditorState& state, const std::string& export_folder);
  void draw_messages();  // a load error, the export's progress or outcome
  void draw_browser(const std::vector<std::string>& takes);
  void list_folder();  // folder_ into dirs_ and files_ (or list_error_)
  // An FBX or glTF file's row: opens to its animations, each a take row.
  void draw_file_with_takes(const std::string& path, const std::vector<std::string>& takes);
  void draw_recent(const EditorState& state, const std::vector<std::string>& takes);
  // The Live section: the address and skeleton fields, Connect / Disconnect, the status line,
  // the recording's field and Record / Stop recording.
  void draw_live(const EditorState& state);
  void sync_live_fields();  // the fields to the live settings, when those changed elsewhere
  void draw_live_status();
  void draw_live_recording();

  LiveSource* live_ = nullptr;
  char live_address_[256] = "", live_skeleton_[512] = "", live_record_[512] = "";
  LiveSettings live_synced_;  // the settings the fields were last filled from
  bool live_fields_filled_ = false;
  std::string live_error_;    // why Connect did nothing (no takes), until the next Connect
  float live_height_ = 24.0f; // the foot's height on the frame before (the export field, the Live section), pixels

  EngineLink& engine_;
  std::string folder_;  // the browser's folder
  std::vector<PathField> fields_;  // one per take (at least two: a pair's B may be empty)
  ExportDialog export_dialog_;  // its file is the export field's (settings().path)
  std::vector<std::string> synced_;  // the requested takes the fields were last filled from
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
