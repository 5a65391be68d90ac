#pragma once
// The canonical frame (DESIGN.md 4): joint positions relative to the hips' ground projection in
// the body's own heading frame, with the root trajectory kept apart so it can be blended and
// placed back in any world frame. Y is up (other up axes are rotated to Y before).
#include <Eigen/Core>

namespace mostyle {

// One take in the canonical frame. F frames, J joints.
struct CanonicalMotion {
  Eigen::MatrixXd local;    // F x 3J: R_y(-heading) (p - ground), file units
  Eigen::MatrixXd ground;   // F x 2: the hips' ground projection (x, z), world, file units
  Eigen::VectorXd heading;  // F: radians about +Y, 0 facing +Z, unwrapped (continuous)
};

// world: F x 3J positions; hips, left_hip, right_hip: joint indices. The heading is the direction
// perpendicular to the left-right hip axis on the ground. Throws InputError on a degenerate hip
// axis in every frame; frames where it is momentarily degenerate keep the previous heading.
CanonicalMotion to_canonical(const Eigen::MatrixXd& world, int hips, int left_hip, int right_hip);

// Root steps, the per-frame root motion in the body frame: row t = (vx, vz, turn) takes frame t
// to t + 1 (ground step rotated into frame t's heading, heading change); the last row is zero.
// F x 3, file units and radians per frame. Blending steps blends speed and turning, whatever
// direction each take walks in.
Eigen::MatrixXd root_steps(const CanonicalMotion& motion);
Eigen::MatrixXd root_steps(const Eigen::MatrixXd& ground, const Eigen::VectorXd& heading);

// Integrates steps (F x 3) from a start position (x, z) and heading into ground (F x 2) and
// heading (F). The inverse of root_steps: integrating a take's own steps from its first frame
// gives its ground and heading back (up to rounding).
void integrate_root(const Eigen::MatrixXd& steps, const Eigen::Vector2d& start_ground,
                    double start_heading, Eigen::MatrixXd* ground, Eigen::VectorXd* heading);

// Places local poses (F x 3J) in the world: p = ground + R_y(heading) local. Writes into `world`
// (resized to F x 3J).
void to_world(const Eigen::MatrixXd& local, const Eigen::MatrixXd& ground,
              const Eigen::VectorXd& heading, Eigen::MatrixXd* world);

}  // namespace mostyle
