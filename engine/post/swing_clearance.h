#pragma once
// Swing clearance (beyond the paper): a foot that the mixed takes hold in the air at a frame is
// kept clear of the floor there. A mix of poses can bring a swinging foot down into the planted
// band (planted_feet.h) where the takes' feet were lifted: a style whose toes skim the floor put
// on a content whose feet swing high, or a style's stance registered onto the content's swing.
// Such a foot moves at swing speed inside the band, reads as a planted foot sliding, and the foot
// lock can only pin it against its own swing. Lifting it out of the band, the whole foot with
// two-bone IK, keeps the feet planted where the takes' are and in the air where theirs are.
#include <Eigen/Core>
#include <vector>

#include "engine/measure/foot_contact.h"

namespace mostyle {

// A foot joint the takes hold more than this many planted bands above its floor is in the air:
// more than one, as their floors and an output's differ a little (an output showing part of a
// take has a floor of its own).
constexpr double kSwingAirBands = 1.0;
// A swinging foot joint is lifted to this many planted bands (kPlantedHeightFraction of the body's
// height) above its floor: clear of the band by a margin, so that rounding and the lock's small
// moves leave it out.
constexpr double kSwingClearanceBands = 1.25;
// The lift eases in and out over this long on either side of where it is needed (smoothstep), so
// a foot rises gradually before a swing begins and comes down gradually after it: no pop.
constexpr double kSwingEaseSeconds = 0.1;

// settle_held_feet turns a foot about its ankle to set its toe's height; the toe's way along that
// arc is at most this many times the change of height asked (a flat foot reaches it within a
// fraction; a steep one is not tipped on end).
constexpr double kToeArcOverChange = 2.0;

struct SwingClearanceScratch {
  Eigen::MatrixXd planted;     // F x kFootJoints (planted_frames)
  std::vector<double> heights;
  Eigen::VectorXd need, lift;  // F: one leg's lift needed on each frame, and eased
  Eigen::MatrixXd total;       // F x 2: each leg's lift over all passes
  Eigen::VectorXd weight;      // F: settle_held_feet's share of one joint's settling
  Eigen::VectorXi from;        // F: the held frame it is read from (-1: none)
};

// Lifts, in world (F x 3M, Y up, file units) itself, each foot joint (planted_feet.h's ankles and
// toes) that is planted (within the band of its floor, planted_frames) on a frame where air
// (F x kFootJoints, planted_feet.h's order) is above 0.5, to kSwingClearanceBands bands above its
// floor: the leg's ankle is raised by the most any of its joints needs there, eased over kSwingEaseSeconds at rig.fps on either side
// (the largest of the eased needs near each frame, so every frame gets at least its own), with
// two-bone IK (the hip stays, thigh and shin keep their lengths, the knee bends in its own plane);
// the toe moves with the ankle. Where the lift raises a joint's floor (the frames lifted were its
// lowest), it lifts again against the new floor, a few passes at most. Frames no lift reaches are
// left exactly as they were. Returns the largest lift, file units. Throws InputError on a shape mismatch or a rig without a body height.
// O(F x w) for w frames of easing; no allocation once scratch has size F.
double lift_swinging_feet(Eigen::MatrixXd& world, const FootRig& rig, const Eigen::MatrixXd& air,
                          SwingClearanceScratch& scratch);

// The counterpart for feet the takes plant: each foot joint the takes hold within the planted band
// (held, F x kFootJoints, above 0.5) that is in the output's band too (planted_frames; a foot the
// output swings is not brought down) set to the height the takes hold it (heights: F x
// kFootJoints, planted bands above the floor, as the foot lock's feet heights), over the output's
// own floor: the ankle raised or lowered with two-bone IK (raise_leg: the knee bends in its own
// plane), then the toe to its height, the foot keeping its length and its way across the floor
// (turned about the ankle along an arc of at most kToeArcOverChange times the change);
// eased over kSwingEaseSeconds on either side of the frames held. A mix of poses changes a
// planted foot's shape where the takes' feet do not (a style's heel lifting, its foot rolling, put
// on a content that stands flat): the ankle then moves across the floor about a toe that stays,
// and no pin of the whole foot holds both. With the takes' heights, the foot rolls as theirs do.
// Returns the largest change, file units. Throws InputError on a shape mismatch. O(F x w); no
// allocation once scratch has size F.
double settle_held_feet(Eigen::MatrixXd& world, const FootRig& rig, const Eigen::MatrixXd& heights,
                        const Eigen::MatrixXd& held, SwingClearanceScratch& scratch);

}  // namespace mostyle
