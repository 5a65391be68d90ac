#pragma once
// The export dialog: the file and its format (BVH, glTF
// or FBX: the buttons set the file's extension), the frame rate (A's own,
// 30, 60, 120 or another), the frames (all, from an in point to an out point, or the blend's
// loop when it has one), the channel layout (engine/export/channel_layout.h, A's default), a
// confirmation before a file is overwritten, and the export on a thread of its own (ExportJob)
// with a progress bar, so the editor stays live and the blend may change meanwhile.
//
// Opened by the files panel's Export button and by Ctrl+E (state.view.show_export); the files
// panel owns it and shares its file field. The last outcome (status()) is shown here and in the
// files panel; new takes clear it.
#include <string>

#include "engine/export/channel_layout.h"
#include "ui/model/engine_link.h"
#include "ui/model/export_job.h"
#include "ui/panels/panel.h"

namespace mostyle::ui {

constexpr const char* kExportDialogTitle = "Export";  // the window's title and ImGui id

enum class ExportRate { kSource, k30, k60, k120, kCustom };

// The last export's outcome as the editor shows it.
struct ExportStatus {
  bool ok = false;
  std::string message;  // where it went, or the error sentence; empty: nothing to say
  double ms = -1.0;     // the last export that wrote a file, wall time; negative: none yet
};

// The file format of an export, which the file's extension decides: BVH, glTF 2.0
// as one .glb (or .gltf with its .bin, typed by hand), or binary FBX (.fbx).
enum class ExportFormat { kBvh, kGltf, kFbx };
// kGltf for .glb and .gltf, kFbx for .fbx, else kBvh (any case).
ExportFormat export_format(const std::string& path);
// `path` with the extension of `format`: ".bvh", ".glb" (a .gltf path stays .gltf for kGltf)
// or ".fbx". A path without an extension gets one; "" stays "".
std::string with_export_format(const std::string& path, ExportFormat format);

// The export's file named after the result (result_name, ui/model/document.h): a bare "blend",
// "mix" or "transfer" (the names the editor gives, with any extension) becomes `result` with that
// extension; a name the animator chose, or one with a folder, stays as it is.
std::string export_name_for(const std::string& path, const std::string& result);

// The output rate `rate` stands for: A's own (source_fps, its file's rate), 30, 60, 120 or
// custom_fps (checked by the export, not here).
double export_rate_fps(ExportRate rate, double source_fps, double custom_fps);

// The dialog's fields, kept from one export to the next.
struct ExportSettings {
  char path[512] = "blend.bvh";   // the file (the files panel's export field edits it too); export_name_for
  ExportRate rate = ExportRate::k30;  // 30: the blend's own frames at the editor's working rate
  double custom_fps = 24.0;
  ExportRange range = ExportRange::kAll;
  double in_s = 0.0, out_s = 0.0;  // kInOut, seconds of the blend; reset to all of it for a new pair
  bool range_in_frames = true;     // the in and out fields count the blend's frames, else seconds
  ChannelLayout layout = ChannelLayout::kRotations;  // default_channel_layout(A) for each new pair
};

class ExportDialog : public Panel {
 public:
  explicit ExportDialog(EngineLink& engine);

  // poll(), the file named after the result shown (export_name_for), then the window while
  // state.view.show_export (closing it clears that).
  void draw(EditorState& state) override;

  // What the dialog's buttons do (also for tests, with no ImGui frame).
  enum class Pressed {
    kStarted,  // the export runs on its thread
    kConfirm,  // the file exists: nothing written, the dialog asks to overwrite it
    kBusy,     // an export is still running: nothing started
    kFailed,   // no file name, no blend, no loop: the sentence is the engine link's export message
  };
  // Export: starts the export, unless the file exists (then asks, kConfirm).
  Pressed press_export();
  // Overwrite, after press_export said kConfirm for the same file: starts the export over it.
  // Without that confirmation it is press_export.
  Pressed press_overwrite();
  // Keep the file (drops the confirmation) or, while an export runs, cancels it.
  void press_cancel();

  // Each frame (draw does it): a new pair resets the range to all of the blend, the layout to
  // A's default and drops a confirmation; the in and out points stay inside the blend; a
  // finished export's outcome becomes status().
  void poll();
  const ExportStatus& status() const { return status_; }

  ExportSettings& settings() { return settings_; }
  // The settings for the engine link's current result: the rate resolved, the range as chosen.
  ExportOptions options() const;
  bool confirming_overwrite() const { return confirm_; }
  // An export runs, or its outcome waits for the next poll(): the editor keeps drawing frames.
  bool busy() const { return job_.running() || job_.has_outcome(); }
  ExportJob& job() { return job_; }
  const ExportJob& job() const { return job_; }

 private:
  Pressed start(bool overwrite);
  // The window's contents, drawn as these steps in this order.
  void draw_contents(EditorState& state, bool* open);
  // The file field and the format buttons; *format: the file's format before the buttons.
  // true: Enter was pressed in the field.
  bool draw_file_fields(ExportFormat* format);
  void draw_rate(const ExportSubject& subject);                           // A's own, 30, 60, 120, other
  void draw_range(const EditorState& state, const ExportSubject& subject);  // all, in to out, the loop
  void draw_in_out_fields(const ExportSubject& subject);                  // typed in frames or seconds
  void draw_in_out_buttons(const EditorState& state, const ExportSubject& subject);  // at the playhead
  void draw_channels(const ExportSubject& subject, ExportFormat format);   // the layout (BVH only)
  void draw_summary(const ExportSubject& subject);  // the frames and rate written, or what is wrong
  // Export and Close; the overwrite question; or the progress and Cancel while busy.
  void draw_actions(bool busy, bool enter, bool* open);
  void draw_status();  // the last outcome

  EngineLink& engine_;
  ExportSettings settings_;
  ExportJob job_;
  ExportStatus status_;
  bool confirm_ = false;      // asking whether to overwrite confirm_path_
  std::string confirm_path_;  // absolute
  const void* seen_pair_ = nullptr;
  bool reset_range_ = true;              // a new pair: in and out to all of its blend once it has one
  std::string named_result_ = "blend";   // the result the file was last named after
  bool typing_range_ = false;  // an in or out field is being typed in: they are put in order after
  std::string folder_;         // EditorState::files_folder: where a file named alone goes
  bool shown_ = false;         // the window was drawn last frame (opened anew: no old outcome shown)
};

}  // namespace mostyle::ui
