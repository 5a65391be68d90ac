#pragma once
// Side by side as parallel lanes: every take walks beside the result, at a fixed
// distance across the result's path, however far the takes' own paths part on a long take. The
// result's hips path gives each frame a lane point and a direction across; a take keeps its own
// pose and facing and has its hips put on its lane. Overlaid, takes keep their own paths.
#include <Eigen/Core>

namespace mostyle::ui {

// Where the takes stand, from the reference's world positions (F x 3J, J joints): its lowest
// joint on y = 0 and its first body centre at the origin (shift), its size (motion_height,
// engine/kinematics/units.h) and side-by-side spacing (spacing_factor times the size), and the
// direction across its overall travel (side; +X when it stands still). O(F x J).
struct Placement {
  Eigen::Vector3d shift = Eigen::Vector3d::Zero();
  Eigen::Vector3d side = Eigen::Vector3d::UnitX();
  float size = 1.0f;
  float spacing = 1.0f;
};
constexpr float kSideBySideSpacing = 0.6f;  // side by side: lateral distance, times the skeleton's size
Placement placement_of(const Eigen::MatrixXd& world, float spacing_factor = kSideBySideSpacing);

// The result's hips path (K x 2, x and z: column 0's ground position) and the direction across
// the lanes (K x 2, unit, the same at every frame): `fallback` (x, z), the reference's overall
// travel turned to the right, so the lanes stand across the camera's view. O(K).
struct Lanes {
  Eigen::MatrixXd path;    // K x 2
  Eigen::MatrixXd across;  // K x 2, unit
};
Lanes lanes_along(const Eigen::MatrixXd& result_world, const Eigen::Vector2d& across);

// world (K x 3J, the take at the result's frames) moved so that at every frame its hips (column
// 0) stand on the lane `offset` units across the path, then shifted by `shift`; frames beyond
// the lanes' use the last lane point. Writes out (K x 3J). O(K x J).
void place_in_lane(const Eigen::MatrixXd& world, const Lanes& lanes, double offset, const Eigen::Vector3d& shift,
                   Eigen::MatrixXd& out);

}  // namespace mostyle::ui
