#pragma once
// What the editor's panels read and change, in one place. The app owns one EditorState and
// hands it to every panel each frame; panels never own engine data of their own. Plain data:
// no GL, no ImGui, so a test can build one by hand.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <glm/glm.hpp>

#include "engine/base/clip.h"
#include "ui/model/cycle_provenance.h"
#include "ui/model/document.h"
#include "ui/model/recent_files.h"

namespace mostyle::ui {

// One motion the editor shows: a loaded (or failed) take, or the result made from the takes
// (a blend, a mix or a transfer), with what its skeleton is drawn with.
struct ShownMotion {
  std::string path;
  std::string label;                      // file name without folder and extension
  std::string error;                      // non-empty: loading failed, shown as it is
  std::vector<std::string> warnings;      // recoverable defects the reader reported
  std::vector<std::string> notes;         // how it was aligned onto the reference, where that changes what plays
  std::shared_ptr<const Clip> clip;       // null when error is set
  Eigen::MatrixXd positions;              // frames x 3*joints, world units (placed, see below)
  std::vector<int> parents;               // per joint, -1 for roots
  std::vector<std::uint8_t> hidden;       // per joint, nonzero: not drawn (a static rig ROOT)
  float size = 1.0f;                      // standing height, world units
  glm::vec3 color{0.8f};                  // sRGB, its skeleton and label
  bool visible = true;
  double fps = 0.0;                       // rate of `positions`; 0: the clip's own
  // Optional, frames x joints: 1 where the joint is planted (the engine's foot contacts);
  // empty: the viewport estimates contacts from the height above the floor.
  Eigen::MatrixXd contacts;
  // The frames of `positions` where one of the take's cycles starts (engine/align/cycles.h), for
  // the timeline's marks; empty: none, or not known.
  std::vector<int> cycle_starts;
  // Optional, one per joint: rgb highlight (sRGB), a = strength (a component's joints).
  std::vector<glm::vec4> highlights;

  bool ok() const { return error.empty() && clip != nullptr; }
  int frames() const { return static_cast<int>(positions.rows()); }
  double rate() const { return fps > 0.0 ? fps : clip ? clip->fps() : 30.0; }
};

struct Playback {
  double time_s = 0.0;   // playhead, seconds from the first frame
  bool playing = true;
  float speed = 1.0f;    // playback rate, 1 = real time
  bool loop = true;
};

struct ViewOptions {
  bool follow = true;     // the camera follows the skeletons as they walk
  bool labels = true;
  bool grid = true;
  bool shadows = true;
  bool contacts = true;
  int samples = 0;        // viewport MSAA samples; 0: automatic (4 on a GPU, 1 on llvmpipe)
  bool request_reframe = false;  // set by a panel: frame the skeletons on the next frame
  bool show_shortcuts = false;        // the window listing every shortcut (F1 or ?)
  bool show_export = false;      // the export dialog (Ctrl+E, the files panel's Export button)
  // Panels take their place from ui/panels/layout.h this frame (ImGuiCond_Always) instead of only the
  // first time: set when the display size changed or on Reset layout, cleared after the panels.
  bool reset_layout = false;
  int laid_out_takes = -1;  // the number of takes the panels were last laid out for (ui/panels/layout.h)
};

// Times the metrics panel shows, in milliseconds, set by the app each frame; negative: not shown
// (a screenshot run shows none: they differ run to run).
struct FrameTimes {
  float frame_ms = -1.0f;     // building one editor frame (CPU)
  float viewport_ms = -1.0f;  // drawing the 3D view (GPU)
  double export_ms = -1.0;    // the last export that wrote a file
};

struct EditorState {
  // Every parameter the animator sets, once (ui/model/document.h): the panels change it, the
  // engine link (EngineLink::sync) brings the engine to it, undo keeps copies of it.
  Document document;
  // Edits of the document given as commands (a key pressed, a click on the timeline) rather than
  // by holding an item: each adds one (command_edited), so that the next EditHistory::record makes
  // them an undo step (an item's edit becomes one when it is let go).
  int command_edits = 0;
  Playback playback;
  ViewOptions view;
  std::vector<ShownMotion> shown;  // the takes, then the result (a blend, a mix or a transfer)
  // Where each cycle of the result shown came from (ui/model/cycle_provenance.h): spans of the
  // reference take's frames (the timeline's), made when a result arrives; empty: no result.
  std::vector<CycleProvenance> cycle_provenance;
  // The takes and sessions opened before, newest first: a take joins when it has loaded (the
  // engine link remembers it), the app keeps the list across restarts.
  RecentFiles recent;
  // Files dropped on the window, waiting for the files panel to load them.
  std::vector<std::string> dropped;
  // Where a file the editor writes goes when it is named without a folder, and where its dialog
  // starts: the session's folder, else the first take's (absolute; the editor sets it each frame).
  // Empty: the working folder.
  std::string files_folder;
  FrameTimes times;

  // The take that sets the timeline (frame numbers, fps, length): the first that loaded.
  const ShownMotion* reference_take() const {
    for (const ShownMotion& t : shown)
      if (t.ok()) return &t;
    return nullptr;
  }
};

// Commands a button and a key both give: one function each, so that they do the same. The
// editor carries them out in the frame they are given (the layout: in the next one when given
// after the panels were drawn).
inline void command_frame_all(EditorState& state) { state.view.request_reframe = true; }
inline void command_reset_layout(EditorState& state) { state.view.reset_layout = true; }
inline void command_toggle_shortcuts(EditorState& state) { state.view.show_shortcuts = !state.view.show_shortcuts; }
inline void command_open_export(EditorState& state) { state.view.show_export = true; }
// After a document edit given by a key or a click (see EditorState::command_edits).
inline void command_edited(EditorState& state) { ++state.command_edits; }

// Time of the last frame of `take`, seconds from the first; 0 without frames.
inline double take_length_s(const ShownMotion& take) { return take.frames() > 1 ? (take.frames() - 1) / take.rate() : 0.0; }

// Moves the playhead on by dt_s x speed while playing. Past the end: back to the start with loop
// on; with loop off it stays on the last frame and playback stops (the button reads Play).
inline void advance_playback(Playback& p, double dt_s, double length_s) {
  if (!p.playing) return;
  p.time_s += dt_s * p.speed;
  if (p.time_s <= length_s) return;
  if (p.loop) {
    p.time_s = 0.0;
  } else {
    p.time_s = length_s;
    p.playing = false;
  }
}

// Play or pause, as the button and the space bar do. Play on the last frame starts again from
// the first (stepping there puts the playhead half a frame past length_s).
inline void toggle_playback(Playback& p, double length_s) {
  if (!p.playing && p.time_s >= length_s) p.time_s = 0.0;
  p.playing = !p.playing;
}

// Frame of `take` at time t (seconds), clamped to its range; 0 for a take without frames.
inline int frame_at(const ShownMotion& take, double time_s) {
  if (!take.ok() || take.frames() == 0) return 0;
  double f = time_s * take.rate();
  int frame = f <= 0.0 ? 0 : static_cast<int>(f + 1e-6);
  return frame >= take.frames() ? take.frames() - 1 : frame;
}

}  // namespace mostyle::ui
