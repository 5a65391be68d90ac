#pragma once
// The left-foot signals before and after warping with matched frames joined (paper Fig. 2), and
// the local-cost matrix with the optimal path. Hover: the matched frames; click: jump there.
#include "ui/model/blend_session.h"
#include "ui/model/dtw_image.h"
#include "ui/panels/panel.h"

namespace mostyle::ui {

// The frames of each take of a pair that its alignment matched, first and last, counted as each
// take's file counts them: B's own frames when it was registered by cycles (not the registered
// take's, which repeats its cycles), each at its file's rate (not the working rate). All 0 for
// a pair not aligned. O(B's matched frames).
struct MatchedFrames {
  int a_first = 0, a_last = 0, b_first = 0, b_last = 0;
};
MatchedFrames matched_frames_in_files(const PreparedTakes& p);

// A take's structure as the "before" plot shades it (engine/align/action_structure.h), in the
// frames it is plotted at: its rests and its actions, [begin, end) each; a take at rest
// throughout is one rest. None for a take registered by cycles (it is plotted as registered,
// its cycles laid on the reference's, where the ticks show its strokes or steps).
struct StructureMarks {
  std::vector<FrameSpan> rests, actions;
};
StructureMarks structure_marks(const PreparedTake& take);

class DtwPanel : public Panel {
 public:
  explicit DtwPanel(BlendSession& session) : session_(session) {}
  void draw(EditorState& state) override;

 private:
  BlendSession& session_;
  DtwCostImage image_;                     // of imaged_, made once per pair
  const PreparedTakes* imaged_ = nullptr;
};

}  // namespace mostyle::ui
