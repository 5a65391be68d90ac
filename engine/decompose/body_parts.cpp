#include "engine/decompose/body_parts.h"

#include <algorithm>
#include <map>

#include "engine/base/error.h"
#include "engine/prepare/major_skeleton.h"

namespace mostyle {

const char* body_region_name(BodyRegion region) {
  switch (region) {
    case BodyRegion::kSpineAndHead: return "spine and head";
    case BodyRegion::kLeftArm: return "left arm";
    case BodyRegion::kRightArm: return "right arm";
    case BodyRegion::kLeftLeg: return "left leg";
    case BodyRegion::kRightLeg: return "right leg";
  }
  return "?";
}

BodyRegion body_region_of(int major) {
  switch (static_cast<MajorJoint>(major)) {
    case MajorJoint::kLeftShoulder:
    case MajorJoint::kLeftElbow:
    case MajorJoint::kLeftWrist:
    case MajorJoint::kLeftHand: return BodyRegion::kLeftArm;
    case MajorJoint::kRightShoulder:
    case MajorJoint::kRightElbow:
    case MajorJoint::kRightWrist:
    case MajorJoint::kRightHand: return BodyRegion::kRightArm;
    case MajorJoint::kLeftHip:
    case MajorJoint::kLeftKnee:
    case MajorJoint::kLeftAnkle:
    case MajorJoint::kLeftToe: return BodyRegion::kLeftLeg;
    case MajorJoint::kRightHip:
    case MajorJoint::kRightKnee:
    case MajorJoint::kRightAnkle:
    case MajorJoint::kRightToe: return BodyRegion::kRightLeg;
    default: return BodyRegion::kSpineAndHead;
  }
}

namespace {
constexpr BodyPart kParts[] = {BodyPart::kLegs,    BodyPart::kArms,     BodyPart::kSpine,   BodyPart::kLeftLeg,
                               BodyPart::kRightLeg, BodyPart::kLeftArm, BodyPart::kRightArm};
}

const char* body_part_name(BodyPart part) {
  switch (part) {
    case BodyPart::kLegs: return "legs";
    case BodyPart::kArms: return "arms";
    case BodyPart::kSpine: return "spine";
    case BodyPart::kLeftLeg: return "left-leg";
    case BodyPart::kRightLeg: return "right-leg";
    case BodyPart::kLeftArm: return "left-arm";
    case BodyPart::kRightArm: return "right-arm";
  }
  return "?";
}

BodyPart parse_body_part(const std::string& name) {
  for (BodyPart p : kParts)
    if (name == body_part_name(p)) return p;
  throw InputError("expected a body part legs, arms, spine, left-leg, right-leg, left-arm or right-arm, found '" +
                   name + "'");
}

bool part_covers(BodyPart part, BodyRegion region) {
  switch (part) {
    case BodyPart::kLegs: return region == BodyRegion::kLeftLeg || region == BodyRegion::kRightLeg;
    case BodyPart::kArms: return region == BodyRegion::kLeftArm || region == BodyRegion::kRightArm;
    case BodyPart::kSpine: return region == BodyRegion::kSpineAndHead;
    case BodyPart::kLeftLeg: return region == BodyRegion::kLeftLeg;
    case BodyPart::kRightLeg: return region == BodyRegion::kRightLeg;
    case BodyPart::kLeftArm: return region == BodyRegion::kLeftArm;
    case BodyPart::kRightArm: return region == BodyRegion::kRightArm;
  }
  return false;
}

int deciding_part(const std::vector<BodyPart>& given, BodyRegion region) {
  int best = -1;
  for (size_t i = 0; i < given.size(); ++i) {
    if (!part_covers(given[i], region)) continue;
    const bool sided = given[i] != BodyPart::kLegs && given[i] != BodyPart::kArms;
    if (best < 0 || (sided && (given[best] == BodyPart::kLegs || given[best] == BodyPart::kArms))) best = static_cast<int>(i);
  }
  return best;
}

std::vector<ComponentJoints> describe_components(const Eigen::MatrixXd& components, const std::vector<int>& majors) {
  std::vector<ComponentJoints> out(static_cast<size_t>(components.rows()));
  std::map<BodyRegion, int> seen;
  for (Eigen::Index k = 0; k < components.rows(); ++k) {
    ComponentJoints& c = out[static_cast<size_t>(k)];
    double best = -1.0;
    for (size_t j = 0; j < majors.size(); ++j) {
      const double energy = components.row(k).segment<3>(3 * static_cast<Eigen::Index>(j)).squaredNorm();
      if (energy == 0.0) continue;
      c.columns.push_back(static_cast<int>(j));
      if (energy > best) {
        best = energy;
        c.centre = static_cast<int>(j);
      }
    }
    if (c.centre >= 0) c.region = body_region_of(majors[static_cast<size_t>(c.centre)]);
    const int n = ++seen[c.region];
    c.name = body_region_name(c.region);
    if (n > 1) c.name += " " + std::to_string(n);
  }
  return out;
}

std::vector<double> weights_for_parts(const std::vector<std::pair<BodyPart, double>>& given,
                                      const std::vector<ComponentJoints>& components, double rest) {
  std::vector<BodyPart> parts;
  for (const auto& [part, weight] : given) parts.push_back(part);
  std::vector<double> out;
  for (const ComponentJoints& c : components) {
    const int decides = deciding_part(parts, c.region);
    out.push_back(decides >= 0 ? given[static_cast<size_t>(decides)].second : rest);
  }
  return out;
}

bool connected_in(const std::vector<int>& columns, const std::vector<int>& parents) {
  if (columns.empty()) return false;
  // A set of tree nodes is connected when exactly one of them has its parent outside the set.
  int tops = 0;
  for (int c : columns) {
    const int p = parents[static_cast<size_t>(c)];
    if (p < 0 || std::find(columns.begin(), columns.end(), p) == columns.end()) ++tops;
  }
  return tops == 1;
}

Eigen::MatrixXd joint_values(const Eigen::MatrixXd& support, const Eigen::MatrixXd& values) {
  const Eigen::Index joints = support.cols() / 3;
  Eigen::MatrixXd out(joints, values.cols());
  const Eigen::RowVectorXd mean = values.colwise().mean();
  for (Eigen::Index j = 0; j < joints; ++j) {
    out.row(j).setZero();
    int count = 0;
    for (Eigen::Index k = 0; k < support.rows(); ++k)
      if (support(k, 3 * j) != 0 || support(k, 3 * j + 1) != 0 || support(k, 3 * j + 2) != 0) {
        out.row(j) += values.row(k);
        ++count;
      }
    if (count > 0) out.row(j) /= double(count);
    else out.row(j) = mean;
  }
  return out;
}

}  // namespace mostyle
