#include "render/skeleton_pose.h"

#include <algorithm>
#include <cassert>

namespace mostyle::render {

bool is_valid(const SkeletonPose& pose, std::string* why) {
  auto fail = [&](const std::string& message) {
    if (why) *why = pose.label + ": " + message;
    return false;
  };
  const size_t n = pose.positions.size();
  if (pose.parents.size() != n) return fail("parents and positions differ in size");
  if (!pose.highlights.empty() && pose.highlights.size() != n)
    return fail("highlights is neither empty nor one per joint");
  if (!pose.contacts.empty() && pose.contacts.size() != n)
    return fail("contacts is neither empty nor one per joint");
  if (!pose.hidden.empty() && pose.hidden.size() != n)
    return fail("hidden is neither empty nor one per joint");
  for (size_t i = 0; i < n; ++i) {
    if (pose.parents[i] < -1 || pose.parents[i] >= static_cast<int>(i))
      return fail("joint " + std::to_string(i) + " has parent " + std::to_string(pose.parents[i]));
  }
  return true;
}

Bounds pose_bounds(const SkeletonPose& pose) {
  Bounds b;
  for (size_t i = 0; i < pose.positions.size(); ++i)
    if (!is_hidden(pose, i)) b.extend(pose.positions[i]);
  return b;
}

float effective_size(const SkeletonPose& pose) {
  if (pose.size > 0.0f) return pose.size;
  glm::vec3 e = pose_bounds(pose).extent();
  if (e.y > 0.0f) return e.y;
  float largest = std::max(e.x, e.z);
  return largest > 0.0f ? largest : 1.0f;
}

glm::vec3 label_anchor(const SkeletonPose& pose) {
  Bounds b = pose_bounds(pose);
  if (b.empty()) return glm::vec3(0.0f);
  glm::vec3 centre = b.center();
  return glm::vec3(centre.x, b.max.y + 0.1f * effective_size(pose), centre.z);
}

std::vector<int> parent_indices(const Skeleton& skeleton) {
  std::vector<int> parents;
  parents.reserve(skeleton.joints.size());
  for (const Joint& j : skeleton.joints) parents.push_back(j.parent);
  return parents;
}

std::vector<glm::vec3> positions_at(const Eigen::MatrixXd& positions, int frame) {
  assert(frame >= 0 && frame < positions.rows());
  assert(positions.cols() % 3 == 0);
  const Eigen::Index joints = positions.cols() / 3;
  std::vector<glm::vec3> out(static_cast<size_t>(joints));
  for (Eigen::Index j = 0; j < joints; ++j) {
    out[static_cast<size_t>(j)] = glm::vec3(static_cast<float>(positions(frame, 3 * j)),
                                            static_cast<float>(positions(frame, 3 * j + 1)),
                                            static_cast<float>(positions(frame, 3 * j + 2)));
  }
  return out;
}

Bounds clip_bounds(const Eigen::MatrixXd& positions) {
  Bounds b;
  const Eigen::Index joints = positions.cols() / 3;
  for (Eigen::Index f = 0; f < positions.rows(); ++f) {
    for (Eigen::Index j = 0; j < joints; ++j) {
      b.extend(glm::vec3(static_cast<float>(positions(f, 3 * j)), static_cast<float>(positions(f, 3 * j + 1)),
                         static_cast<float>(positions(f, 3 * j + 2))));
    }
  }
  return b;
}

void mark_ground_contacts(SkeletonPose* pose, float ground_height, float tolerance) {
  pose->contacts.assign(pose->positions.size(), 0);
  for (size_t i = 0; i < pose->positions.size(); ++i) {
    pose->contacts[i] = pose->positions[i].y - ground_height <= tolerance ? 1 : 0;
  }
}

}  // namespace mostyle::render
