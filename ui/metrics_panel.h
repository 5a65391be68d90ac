#pragma once
// Reconstruction error, bone-length error, foot sliding, stage times and the frame time, in
// plain words with units: lengths in centimetres when the file's unit can be guessed from the
// skeleton's height (engine/kinematics/units.h), else as a percentage of that height.
#include <string>

#include "ui/blend_session.h"
#include "ui/panel.h"

namespace mostyle::ui {

// Centimetres per file unit for a unit name of guess_units() ("metres", "inches", "CMU units
// (1/0.45 inch)", ...); 0 for a name it does not know ("unknown").
double centimetres_per_unit(const std::string& unit_name);

// A length (or speed, with per = "/s") of `value` file units in words: "1.5 cm", "4.2 mm",
// "1.23 m", or, when cm_per_unit is 0, "2.1% of height" of a skeleton `height` units tall
// ("-" when neither is known).
std::string length_in_words(double value, double cm_per_unit, double height, const char* per = "");

class MetricsPanel : public Panel {
 public:
  explicit MetricsPanel(BlendSession& session) : session_(session) {}
  void draw(EditorState& state) override;

 private:
  BlendSession& session_;
  // A's unit, guessed once per loaded pair.
  const PreparedPair* unit_pair_ = nullptr;
  double cm_per_unit_ = 0.0;
  double height_ = 0.0;  // A's standing height, file units
  std::string unit_name_;
};

}  // namespace mostyle::ui
