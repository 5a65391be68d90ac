#pragma once
// What length unit a clip is probably in, from the size of its skeleton.
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

}  // namespace mostyle
