#pragma once
// What the renderer draws for one skeleton at one instant: joint positions, the tree, a
// colour and a label, plus optional per-joint highlights and ground contacts. A plain value,
// rebuilt every frame from engine data (positions_at() converts the engine's Eigen rows).
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <glm/glm.hpp>

#include "engine/base/clip.h"
#include "render/bounds.h"

namespace mostyle::render {

struct SkeletonPose {
  std::string label;                 // shown by the UI next to the skeleton (render draws no text)
  glm::vec3 color{0.8f, 0.8f, 0.8f}; // sRGB in [0, 1]
  std::vector<glm::vec3> positions;  // per joint, world units, Y up
  std::vector<int> parents;          // per joint: parent index (< own index), -1 for a root
  // Optional, empty or one per joint: rgb = highlight colour (sRGB), a = strength in [0, 1].
  // Lights up a joint and the bone that ends at it, e.g. the joints of one component.
  std::vector<glm::vec4> highlights;
  // Optional, empty or one per joint: nonzero = the joint touches the ground (a marker is
  // drawn on the ground under it).
  std::vector<std::uint8_t> contacts;
  // Optional, empty or one per joint: nonzero = not drawn, nor its bones, shadow or marker
  // (e.g. a static reference ROOT on the floor under a game rig's hips).
  std::vector<std::uint8_t> hidden;
  // Characteristic size (standing height) in world units, for bone thickness and shadow size.
  // Keep it constant over a clip (engine/kinematics/units.h motion_height) so bones do not swell
  // when a pose crouches;
  // 0: take this pose's own height.
  float size = 0.0f;
};

// Checks the invariants above; false (and *why) when the sizes disagree or a parent index is
// not smaller than its joint's. The renderers skip invalid poses instead of reading out of range.
bool is_valid(const SkeletonPose& pose, std::string* why = nullptr);

Bounds pose_bounds(const SkeletonPose& pose);  // of the visible joints
// pose.size when positive, else the pose's vertical extent, else its largest extent, else 1.
float effective_size(const SkeletonPose& pose);
inline bool is_hidden(const SkeletonPose& pose, size_t joint) {
  return !pose.hidden.empty() && pose.hidden[joint] != 0;
}

// Where a label goes: above the highest visible joint, by a tenth of the size.
glm::vec3 label_anchor(const SkeletonPose& pose);

// ---- Conversion from engine data -----------------------------------------------------------

// Parent index per joint (End Sites included, skeleton order), -1 for roots. O(joints).
std::vector<int> parent_indices(const Skeleton& skeleton);

// Row `frame` of positions (frames x 3*joints, file units; what joint_positions() returns) as
// one vec3 per joint. Asserts frame in [0, rows) and cols divisible by 3.
std::vector<glm::vec3> positions_at(const Eigen::MatrixXd& positions, int frame);

// Box around every joint of every frame (frames x 3*joints). Empty for an empty matrix.
Bounds clip_bounds(const Eigen::MatrixXd& positions);

// Marks joints that are within `tolerance` (world units) of the ground height: a display aid
// for the contact markers, not an analysis. Resizes pose->contacts to the joint count.
void mark_ground_contacts(SkeletonPose* pose, float ground_height, float tolerance);

}  // namespace mostyle::render
