#pragma once
// The style palette in the editor: the takes the viewport shows while a palette is
// loaded, and the mix, re-run on the UI thread when a weight or option moves (well under a
// millisecond for a minute of eight takes). The palette and its decomposition come from the
// engine's worker (BlendSession); this file only turns them into what is shown.
//
// EditorState::takes while a palette is loaded: [0] the mix, then one take per palette take
// (the reference first), each shown at the frame the mix is in it.
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "engine/run/palette.h"
#include "ui/model/editor_state.h"

namespace mostyle::ui {

struct DocumentControls;
struct PaletteControls;

constexpr int kPaletteMix = 0;    // index of the mix in EditorState::takes
constexpr int kPaletteFirst = 1;  // index of the reference; take i is at kPaletteFirst + i

// The engine's mix parameters the controls ask for (weights kept to the palette's size, the keys
// when they fit the takes (ui/model/keyed_weights.h), per-part weights, a transfer's weights, the
// clean-up options). Throws InputError when the weights or keys are refused (MixParams::Validate
// says why).
MixParams mix_params_for(const DocumentControls& controls, const Decomposed& decomposition, int takes);

// The weights of takes `after` when they are the takes `before` (weighted `weights`, one per
// take; a pair's are (1 - alpha, alpha)) with more added: each take that was there keeps its
// weight, each one added gets 0 (a pair at 0.7/0.3 given a third take is 0.7/0.3/0). Empty when
// no take is added (as many or fewer takes) or none of `before` is among `after`, or the weights
// do not fit `before`: then the palette's own rule applies (equal weights for a new palette).
// O(after x before).
std::vector<double> weights_with_added_takes(const std::vector<std::string>& before, const std::vector<double>& weights,
                                             const std::vector<std::string>& after);

// The palette's colour of take i (the reference first).
glm::vec3 palette_color(int take);

class PaletteView {
 public:
  // A new palette: the mix and one take per palette take, on the reference's floor and start.
  void take_up(const PreparedTakes& palette, const std::vector<std::string>& paths,
               const std::vector<std::string>& warnings, PaletteControls& controls, EditorState& state);
  // After the panels: mixes again when the controls' mix differs from the one shown, then
  // refreshes positions, visibility (ghosts) and placement.
  void update(const PreparedTakes& palette, const Decomposed* decomposition,
              const DocumentControls& controls, EditorState& state);
  void clear();

  const MixResult* mix() const { return has_mix_ ? &mix_ : nullptr; }
  const Eigen::Vector3d& side() const { return side_; }  // the lanes' direction across (ui/model/lanes.h)
  const std::string& error() const { return error_; }
  double mix_ms() const { return mix_ms_; }
  const StageTimes& mix_times() const { return mix_times_; }  // its stages (synthesize, postprocess)

 private:
  void place(const PreparedTakes& palette, const DocumentControls& controls, EditorState& state);

  const Decomposed* mixed_decomposition_ = nullptr;
  MixParams mixed_;
  MixScratch scratch_;
  MixResult mix_;
  bool has_mix_ = false;
  bool placed_overlay_ = false, placed_ghosts_ = false;
  std::string error_;
  std::vector<std::string> names_;  // each take's name (its file's), for cycle_provenance
  double mix_ms_ = 0.0;
  StageTimes mix_times_;
  Eigen::Vector3d shift_ = Eigen::Vector3d::Zero(), side_ = Eigen::Vector3d::UnitX();
  float spacing_ = 0.0f;
};

}  // namespace mostyle::ui
