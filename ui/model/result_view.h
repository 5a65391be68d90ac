#pragma once
// What the viewport shows of the loaded takes and their result, for any number of takes (a pair
// and a palette alike): one take per loaded take and the result (the blend, mix or transfer), all
// on the result's timeline, placed on the reference's floor and start. The result is mixed again
// (mix_palette, on the UI thread) when the document's mix fields change (the field list:
// document_fields.h, Stale::kMix) or a new decomposition arrives. While a slider is held the mix
// is a preview (the poses, the root and the limb lengths: under a millisecond for a minute of
// eight takes), and the foot lock and the measures follow once it is let go (finish_mix_palette:
// the same result as one whole mix). The takes and their decomposition come from the engine's worker
// (EngineLink); this file only turns them into what is shown.
//
// EditorState::takes while takes are loaded: take i at i (the reference first), the result last.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "engine/synthesize/mix_palette.h"
#include "ui/model/document.h"
#include "ui/model/editor_state.h"

namespace mostyle::ui {

// The index of the result in EditorState::takes for `takes` loaded takes (after them).
constexpr int result_index(int takes) { return takes; }

// The colour of take i (the reference first): a pair's A orange and B blue, then violet, yellow,
// pink, teal, ... around the wheel.
glm::vec3 take_color(int take);
// The result's colour: green, between the takes' colours.
glm::vec3 result_color();

// One take as the viewport shows it, for whatever makes the takes shown (ResultView; the live
// source, ui/model/live_source.h): its label, colour, clip, the rate of `positions` (frames x
// 3*joints, world units) and the joints' parents; the rest at Take's defaults.
ShownMotion shown_take(std::string label, glm::vec3 color, std::shared_ptr<const Clip> clip, double fps,
                std::vector<int> parents, Eigen::MatrixXd positions);

class ResultView {
 public:
  // New takes: one ShownMotion each and the result, on the reference's floor and start. paths: the
  // takes' files; warnings: the load's, each filed under the take it names.
  void take_up(const PreparedTakes& takes, const std::vector<std::string>& paths, const std::vector<std::string>& warnings,
               EditorState& state);
  // After the panels: mixes again when the document's mix differs from the one shown or the
  // decomposition is new (a preview while item_held: an ImGui item is being dragged), finishes a
  // preview once nothing is held, then refreshes the result's label, the highlighted component,
  // and the placement when the overlay or ghosts changed.
  void update(const PreparedTakes& takes, const Decomposed* decomposition, EditorState& state, bool item_held);
  // The result shown is a preview still to be finished.
  bool previewing() const { return scratch_.pending.waiting; }
  void clear();

  const MixResult* mix() const { return has_mix_ ? &mix_ : nullptr; }
  const Eigen::Vector3d& side() const { return side_; }  // the lanes' direction across (ui/model/lanes.h)
  const std::string& error() const { return error_; }
  double mix_ms() const { return mix_ms_; }  // the last mix (a preview, or with its finish), wall time
  const StageTimes& mix_times() const { return mix_times_; }  // its stages (synthesize, postprocess)

 private:
  void remix(const PreparedTakes& takes, const Decomposed& decomposition, EditorState& state, bool preview);
  void finish(const PreparedTakes& takes, EditorState& state);
  void take_up_mix(const PreparedTakes& takes, EditorState& state);
  void place(const PreparedTakes& takes, EditorState& state);
  void highlight(const Decomposed* decomposition, EditorState& state) const;

  const Decomposed* mixed_decomposition_ = nullptr;
  Document mixed_;  // the document as last mixed (its mix fields are what is shown)
  MixParams mixed_params_;  // what it was mixed with (a preview's, for its finish)
  MixScratch scratch_;
  MixResult mix_;
  bool has_mix_ = false;
  bool placed_overlay_ = false, placed_ghosts_ = false;
  std::string error_;
  std::vector<std::string> names_;  // each take's name in the result's provenance ("A", "B"; or its label)
  double mix_ms_ = 0.0;
  StageTimes mix_times_;
  Eigen::Vector3d shift_ = Eigen::Vector3d::Zero(), side_ = Eigen::Vector3d::UnitX();
  float spacing_ = 0.0f;
  Eigen::MatrixXd sampled_;  // one take's rows at the result's frames (place's scratch)
};

}  // namespace mostyle::ui
