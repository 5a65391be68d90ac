#pragma once
// What length unit a clip is probably in, from the size of its skeleton, and how tall a motion is.
#include <Eigen/Core>
#include <string>

#include "engine/base/clip.h"

namespace mostyle {

struct UnitsGuess {
  double height = 0.0;  // vertical extent of the first frame's joints, file units
  double size = 0.0;    // diagonal of the first frame's bounding box, file units
  std::string name;     // "centimetres", "metres", "inches", "CMU units (1/0.45 inch)", ...
};

// Guesses from the first frame (the rest pose when there are no frames), assuming a human of
// about 1.5 to 1.9 m and Y up.
UnitsGuess guess_units(const Clip& clip);

// Centimetres per file unit for a unit name guess_units gives ("metres", "inches", "CMU units
// (1/0.45 inch)", ...); 0 for a name it does not know ("unknown").
double centimetres_per_unit(const std::string& unit_name);

// Metres per file unit: the skeleton's own (Skeleton::metres_per_unit) where its file states one,
// else from guess_units (centimetres_per_unit / 100); 0 when neither tells (a skeleton whose
// height is no human's, from a file without a unit). What the writers of files with a unit
// (glTF's metres, FBX's UnitScaleFactor) scale by. O(joints), O(1) when the unit is stated.
double metres_per_unit(const Clip& clip);

// How tall a motion stands: the largest vertical (Y) extent of a single frame, over all frames.
// positions: frames x 3J, file units; 0 without frames. One value for the whole clip, so a
// crouch does not shrink it. O(frames x J).
double motion_height(const Eigen::MatrixXd& positions);

}  // namespace mostyle
