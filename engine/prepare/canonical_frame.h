#pragma once
// The canonical frame: joint positions relative to the hips' ground projection in
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

// Take B's root path moved rigidly so that at B's (fractional) frame b_frame it stands where A
// stands at a_frame and faces where A faces: both then walk from one place. Ground: B's frames x 2,
// heading: B's frames.
struct PlacedRoot {
  Eigen::MatrixXd ground;
  Eigen::VectorXd heading;
};
PlacedRoot place_at(const CanonicalMotion& a, double a_frame, const CanonicalMotion& b, double b_frame);

// Places local poses (F x 3J) in the world: p = ground + R_y(heading) local. Writes into `world`
// (resized to F x 3J).
void to_world(const Eigen::MatrixXd& local, const Eigen::MatrixXd& ground,
              const Eigen::VectorXd& heading, Eigen::MatrixXd* world);

}  // namespace mostyle
