#pragma once
// Side by side as parallel lanes (issue #10): every take walks beside the result, at a fixed
// distance across the result's path, however far the takes' own paths part on a long take. The
// result's hips path gives each frame a lane point and a direction across; a take keeps its own
// pose and facing and has its hips put on its lane. Overlaid, takes keep their own paths.
#include <Eigen/Core>

namespace mostyle::ui {

// The result's hips path (K x 2, x and z: column 0's ground position) and, per frame, the unit
// direction across it (K x 2): to the right of the direction of travel, smoothed over
// half_window frames each side; where the result stands still, `fallback` (x, z). O(K).
struct Lanes {
  Eigen::MatrixXd path;    // K x 2
  Eigen::MatrixXd across;  // K x 2, unit
};
Lanes lanes_along(const Eigen::MatrixXd& result_world, const Eigen::Vector2d& fallback, int half_window = 15);

// world (K x 3J, the take at the result's frames) moved so that at every frame its hips (column
// 0) stand on the lane `offset` units across the path, then shifted by `shift`; frames beyond
// the lanes' use the last lane point. Writes out (K x 3J). O(K x J).
void place_in_lane(const Eigen::MatrixXd& world, const Lanes& lanes, double offset, const Eigen::Vector3d& shift,
                   Eigen::MatrixXd& out);

}  // namespace mostyle::ui
