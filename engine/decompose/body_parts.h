#pragma once
// Body parts: which region of the body each local component moves, named in plain
// words, and the parts an animator gives weights to ("legs from one take, arms from another").
#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

namespace mostyle {

enum class BodyRegion { kSpineAndHead, kLeftArm, kRightArm, kLeftLeg, kRightLeg };
const char* body_region_name(BodyRegion region);  // "spine and head", "left arm", ...
BodyRegion body_region_of(int major);             // of a canonical joint (major_skeleton.h)

// The parts weights can be given to: a region, or a pair of them.
enum class BodyPart { kLegs, kArms, kSpine, kLeftLeg, kRightLeg, kLeftArm, kRightArm };
const char* body_part_name(BodyPart part);        // "legs", "arms", "spine", "left-leg", ...
BodyPart parse_body_part(const std::string& name);  // throws InputError naming the choices
bool part_covers(BodyPart part, BodyRegion region);
// Of several parts given, the one that decides a region: the most specific (a side before both
// sides), else -1. parts: indices into `given`.
int deciding_part(const std::vector<BodyPart>& given, BodyRegion region);

struct ComponentJoints {
  std::vector<int> columns;  // major-joint columns with a non-zero entry, in column order
  int centre = -1;           // the column with the most energy
  BodyRegion region = BodyRegion::kSpineAndHead;  // the centre's
  std::string name;          // plain words: "left leg", "left leg 2", ... (numbered within a region)
};

// components: k x 3M (C); majors: the canonical joint of each column (M). O(k x M).
std::vector<ComponentJoints> describe_components(const Eigen::MatrixXd& components, const std::vector<int>& majors);

// One weight per component from weights given per body part: each component takes the weight
// of the part that decides its region (deciding_part), else `rest`.
std::vector<double> weights_for_parts(const std::vector<std::pair<BodyPart, double>>& given,
                                      const std::vector<ComponentJoints>& components, double rest);

// Per joint, values given per component: support is k x 3M (non-zero where component c moves a
// channel), values k x n (n values per component, e.g. one weight per take). Row j of the result
// (M x n) is the mean of the rows of the components that move joint j, or the mean of all rows
// when none does: a body part's residual detail follows its part. O(k x 3M x n).
Eigen::MatrixXd joint_values(const Eigen::MatrixXd& support, const Eigen::MatrixXd& values);

// Whether `columns` form one connected piece of the tree `parents` (within-column parents, -1
// for a root). Empty: false.
bool connected_in(const std::vector<int>& columns, const std::vector<int>& parents);

}  // namespace mostyle
