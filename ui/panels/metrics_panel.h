#pragma once
// Reconstruction error, bone-length error, foot sliding, stage times and the frame time, and a
// live stream's rate, latency and skipped frames, in plain words with units: lengths in centimetres when the file's unit can be guessed from the
// skeleton's height (engine/kinematics/units.h), else as a percentage of that height.
#include <string>
#include <vector>

#include "engine/synthesize/mix_measures.h"
#include "ui/model/engine_link.h"
#include "ui/model/live_source.h"
#include "ui/panels/panel.h"

namespace mostyle::ui {

// What the metrics panel shows, gathered from the engine link for any number of takes alike: the
// takes' names, the measures the CLI reports (engine/synthesize/mix_measures.h) and the stages'
// times; a negative time is not known yet ("-").
struct Metrics {
  const Clip* reference = nullptr;  // the take whose units every length is in
  std::string result = "blend";     // result_name (ui/model/document.h): "blend", "mix" or "transfer"
  std::vector<std::string> take_names;  // "A", "B" in a pair, else what tells the takes' names apart
  // The takes' and the result's (none while no result is shown, or a preview is not finished).
  MixMeasures measures;
  double load_ms = -1.0, preprocess_ms = -1.0, dtw_ms = -1.0, decompose_ms = -1.0;
  double synthesize_ms = -1.0, postprocess_ms = -1.0, result_ms = -1.0;
};
// O(takes): no copy of any motion. transfer: the takes are in transfer mode (the document's).
Metrics gather_metrics(const EngineLink& engine, bool transfer);

class MetricsPanel : public Panel {
 public:
  explicit MetricsPanel(EngineLink& engine) : engine_(engine) {}
  void draw(EditorState& state) override;
  // The live source whose rate, latency and skipped frames are shown first while it runs; none:
  // not shown.
  void set_live(const LiveSource* live) { live_ = live; }

 private:
  // The steps of draw, in its order.
  void guess_unit(const Clip* reference);  // once per reference take (null: none)
  // `value` (reference units, negative: "-") in words: centimetres, or a share of the height.
  std::string length(double value, const char* per = "") const;
  // A speed of planted feet (reference units per second) as the CLI says it: a share of the body's
  // height per second ("0.85%h/s"); "-" without a height.
  static std::string planted_speed(double value, double body_height);
  // The unit lengths are shown in; the reference take named `reference` ("take A", "the
  // reference take").
  void draw_unit_note(const char* reference);
  void draw_takes_table(const Metrics& m);                            // fit error and foot sliding per take
  void draw_quality_table(const Metrics& m, const char* reference);   // the result's bones and feet
  void draw_times_table(const Metrics& m, const FrameTimes& times);  // each stage's time
  void draw_live_table();  // the live source's, once it has been connected

  const LiveSource* live_ = nullptr;

  EngineLink& engine_;
  // The reference's unit, guessed once per loaded reference take.
  const Clip* unit_clip_ = nullptr;
  double cm_per_unit_ = 0.0;
  double height_ = 0.0;  // A's standing height, file units
  std::string unit_name_;
};

}  // namespace mostyle::ui
