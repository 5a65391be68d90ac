#pragma once
// Re-expressing a clip's rotations in another Euler order.
#include "engine/base/clip.h"
#include "engine/kinematics/euler.h"

namespace mostyle {

// The same motion with every rotating joint's channels rewritten as its position channels (in
// their file order) followed by three rotation channels in `order`. Angles are unwrapped frame
// to frame (no jumps over 180 degrees), so curves stay smooth. Joint positions are unchanged.
Clip convert_euler_order(const Clip& clip, EulerOrder order);

// The rotation order of a joint with exactly three rotation channels; false otherwise.
bool joint_euler_order(const Joint& joint, EulerOrder* order);

}  // namespace mostyle
