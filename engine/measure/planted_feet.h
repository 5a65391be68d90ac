#pragma once
// Planted feet: the one measure of how fast a motion's planted feet move over the floor, the same
// for every take and every output (a blend, a mix, a transfer), before and after the foot lock.
// A foot joint (each ankle, and each toe where the rig has one) is planted on a frame when it is
// within kPlantedHeightFraction of the body's height (FootRig::body_height) above its own floor,
// the kPlantedFloorPercentile of its height over the motion; a frame step t -> t + 1 counts when
// the joint is planted at both t and t + 1. The measure is the mean horizontal (x, z) speed over
// those steps, all foot joints pooled. Only heights decide what is planted, so a lock that moves
// the feet horizontally (and keeps their heights) leaves the same steps planted.
#include <Eigen/Core>
#include <array>
#include <cmath>
#include <vector>

#include "engine/measure/foot_contact.h"

namespace mostyle {

constexpr double kPlantedHeightFraction = 0.03;  // of the body's height above the joint's floor
constexpr double kPlantedFloorPercentile = 0.05; // of the joint's heights over the motion: its floor
constexpr int kFootJoints = 4;                   // left ankle, left toe, right ankle, right toe

// The horizontal length of a step (dx, dz), file units: sqrt(dx^2 + dz^2), as std::hypot within
// rounding (no overflow or underflow to guard against at a motion's scale) at a fraction of its
// cost, which the foot lock's tries pay thousands of times.
inline double horizontal_step(double dx, double dz) { return std::sqrt(dx * dx + dz * dz); }

// The columns measured, in the order of kFootJoints (-1 where the rig has none or the leg is not
// usable).
std::array<int, kFootJoints> foot_joint_columns(const FootRig& rig);

// How fast a motion's planted feet move.
struct PlantedSpeed {
  double speed = 0.0;   // mean horizontal speed over the planted steps, file units per second; 0 when none
  long steps = 0;       // planted steps, all foot joints pooled
  double height = 0.0;  // the body height the planted threshold and of_height() take, file units
  double of_height() const { return height > 0.0 ? speed / height : 0.0; }  // body heights per second
};

// F x kFootJoints: 1 where that foot joint is planted on that frame, else 0 (a column the rig lacks
// is all 0). world: F x 3M, Y up. heights: scratch, resized to F. floors: when given, each
// joint's floor height (0 for a joint the rig lacks). band_scale: the band that many times as
// high (1: the measure's). Throws InputError when a column is beyond world's or rig.body_height
// is not positive. O(F) (the percentile by selection), no allocation once planted and heights
// are sized.
void planted_frames(const Eigen::MatrixXd& world, const FootRig& rig, Eigen::MatrixXd& planted,
                    std::vector<double>& heights, std::array<double, kFootJoints>* floors = nullptr,
                    double band_scale = 1.0);

// The measure from planted (F x kFootJoints, planted_frames) at rig.fps. Throws InputError on a
// shape mismatch. O(F), no allocation.
PlantedSpeed planted_speed(const Eigen::MatrixXd& world, const Eigen::MatrixXd& planted, const FootRig& rig);

// Both in one: the measure of world (F x 3M). Allocates its masks. O(F).
PlantedSpeed planted_speed(const Eigen::MatrixXd& world, const FootRig& rig);

// The body's height every planted threshold takes: the reference's major joints stood upright
// from their bone lengths (lengths, parallel to majors, bone_lengths()): the leg (thigh and shin,
// averaged over the usable legs) below the hips and the trunk (hips to spine, chest and head, as
// far as the skeleton has them) above. A pose-free length of the reference alone, the same for
// its every take and output. 0 when there is no usable leg. O(M).
double standing_height(const std::vector<int>& majors, const std::vector<double>& lengths);

}  // namespace mostyle
