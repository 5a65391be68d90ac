#pragma once
// Strides fitted to the root's pace (beyond the paper). A root kept near another path than the
// one its poses were made for (a transfer whose content is its own neutral keeps the content's
// path, trajectory/mixed_root.h keep_near_path) goes at a pace its legs do not step: the style
// take's stride under the content's travel. A planted foot moves under the body as fast as the
// body goes over it, so such a foot slides by the difference, and where a step is longer than the
// leg reaches the foot lock cannot hold it. The feet's place under the body is mapped, frame by
// frame, so that a foot held still under the free root's travel is held still under the kept
// root's: the stride shortens (or lengthens) with the pace, as a walker's does.
#include <Eigen/Core>

#include "engine/measure/foot_contact.h"

namespace mostyle {

// A stride is stretched no further than the leg reaches short of straight by this fraction.
constexpr double kStrideReachMargin = 0.02;

// Maps the legs' feet in local (K x 3M canonical poses: body frame, x across, y up, z the way
// the body faces; canonical_frame.h) by map (K x 4: each frame's 2 x 2 map on (x, z), row-major,
// trajectory/mixed_root.h stride_map): each usable leg's ankle is moved to the map of its (x, z),
// its height kept, by two-bone IK from the hip (thigh and shin keep their lengths, the knee bends
// in its own plane, forwards where the leg is straight), and no further than the leg reaches
// (kStrideReachMargin): a stretched stride stops where the leg would straighten. The toe follows
// the ankle, the foot's length and pitch kept and the way it points across the floor mapped. A
// map of the identity leaves the frame as it is. Throws InputError when map's rows differ from
// local's or it has not 4 columns. O(K).
void warp_strides(Eigen::MatrixXd& local, const Eigen::MatrixXd& map, const FootRig& rig);

}  // namespace mostyle
