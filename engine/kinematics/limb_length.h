#pragma once
// Limb-length constraint (paper 3.7): synthesized positions get the reference
// skeleton's bone lengths back, bone directions kept, from the root outward.
#include <Eigen/Core>
#include <vector>

namespace mostyle {

// Joints: positions hold joint j in columns 3j..3j+2 (x, y, z); parents[j] is j's parent index
// (< j: parents before children) or -1 for a root. A skeleton may have several roots.

struct LimbLengthOptions {
  // A bone shorter than degenerate_fraction * its reference length has no usable direction
  // (child on top of parent). It then takes the direction it has in the previous output frame;
  // in the first frame, its direction in fallback_pose (1 x 3J, e.g. A's first frame) when given
  // and itself usable, else +Y (the up axis). The rule keeps the skeleton continuous in time.
  double degenerate_fraction = 1e-9;
  Eigen::RowVectorXd fallback_pose;  // empty, or 1 x 3J positions
  // A bone shorter than short_fraction * its length turns from its previous output frame's
  // direction towards its own by the fraction (|bone| / (short_fraction L))^2 of the angle
  // between them: blending two takes whose limbs point different ways can shorten a bone to
  // almost nothing, and stretching it back along its own direction would swing the limb round
  // within a frame. 0: off (every usable bone keeps its own direction).
  double short_fraction = 0.0;
};

// Applies the constraint in place. positions: frames x 3J, file units; lengths: J values (file
// units, >= 0; roots' values are ignored), usually bone_lengths() of the reference take.
// Per joint with a parent: child = parent' + L * unit(child - parent), parent' the already
// corrected parent and (child - parent) the bone as it was before correction, so each bone
// keeps its direction and each subtree moves rigidly with its root. Roots do not move.
// Throws InputError when the shapes do not match, a parent index is not < its joint, a length
// is negative or not finite, or an option is out of range. O(frames * J); no allocation.
void apply_limb_lengths(Eigen::MatrixXd& positions, const std::vector<int>& parents,
                        const std::vector<double>& lengths, const LimbLengthOptions& options = {});

// Mean bone length over frames, per joint (J values, 0 for roots). positions: frames x 3J, one
// row (a single pose) or more. Throws InputError on bad shapes or parents, or no frames.
std::vector<double> bone_lengths(const Eigen::MatrixXd& positions, const std::vector<int>& parents);

// max over frames and non-root joints of | |child - parent| - lengths[j] |, file units; 0 with no
// bones. Throws InputError on bad shapes or parents.
double max_bone_length_error(const Eigen::MatrixXd& positions, const std::vector<int>& parents,
                             const std::vector<double>& lengths);

}  // namespace mostyle
