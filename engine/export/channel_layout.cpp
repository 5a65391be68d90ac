#include "engine/export/channel_layout.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <locale>
#include <sstream>
#include <vector>

#include "engine/base/error.h"
#include "engine/kinematics/kinematics.h"

namespace mostyle {
namespace {

bool has_position_channel(const Joint& joint) {
  return std::any_of(joint.channels.begin(), joint.channels.end(), is_position);
}

// The clip's size for the relative tolerance: the longest bone below the root, as the OFFSETs
// give it and as frame 0's position channels do (a file with zero OFFSETs and every bone in its
// channels has a size too). Roots are left out: where a take starts is not its size.
double clip_size(const Clip& clip) {
  double size = 0.0;
  for (const Joint& joint : clip.skeleton.joints) {
    if (joint.parent < 0) continue;
    size = std::max(size, joint.offset.norm());
    if (clip.frames() > 0 && has_position_channel(joint))
      size = std::max(size, joint_local_translation(joint, clip.motion.row(0).data()).norm());
  }
  return size > 0.0 ? size : 1.0;
}

// Where one of a joint's position channels first leaves frame 0's value by more than `limit`.
struct Change {
  int frame = -1;    // 0-based; -1: the channels keep one value
  int channel = -1;  // index into Joint::channels
};

Change first_change(const Clip& clip, const Joint& joint, double limit) {
  for (int f = 1; f < clip.frames(); ++f) {
    for (size_t c = 0; c < joint.channels.size(); ++c) {
      if (!is_position(joint.channels[c])) continue;
      const int column = joint.first_channel + static_cast<int>(c);
      // Written so that a NaN counts as a change.
      if (!(std::abs(clip.motion(f, column) - clip.motion(0, column)) <= limit))
        return {f, static_cast<int>(c)};
    }
  }
  return {};
}

// Which joints keep their position channels in the rotations layout, and the first joint that
// cannot lose them.
struct RotationsPlan {
  int trajectory_child = -1;  // a child of a root whose position channels change, or -1
  int changing = -1;          // a joint to fold whose position channels change, or -1
  Change change;              // where `changing` changes
};

RotationsPlan plan_rotations(const Clip& clip, double tolerance) {
  assert(tolerance >= 0.0 && "tolerance is a fraction of the clip's size");
  const std::vector<Joint>& joints = clip.skeleton.joints;
  const double limit = tolerance * clip_size(clip);
  RotationsPlan plan;
  for (int j = 0; j < static_cast<int>(joints.size()); ++j) {
    const Joint& joint = joints[j];
    if (joint.parent < 0 || !has_position_channel(joint)) continue;
    const Change change = first_change(clip, joint, limit);
    if (change.frame < 0) continue;
    // One child of the root may carry the trajectory (Bandai's Hips below the still joint_Root);
    // the first such in file order does.
    if (plan.trajectory_child < 0 && joints[joint.parent].parent < 0) {
      plan.trajectory_child = j;
      continue;
    }
    plan.changing = j;
    plan.change = change;
    return plan;
  }
  return plan;
}

std::string format_number(double value) {
  std::ostringstream out;
  out.imbue(std::locale::classic());
  out << value;
  return out.str();
}

}  // namespace

const char* channel_layout_name(ChannelLayout layout) {
  switch (layout) {
    case ChannelLayout::kAsSource: return "as-source";
    case ChannelLayout::kRotations: return "rotations";
  }
  return "?";
}

ChannelLayout parse_channel_layout(const std::string& name) {
  for (ChannelLayout layout : {ChannelLayout::kAsSource, ChannelLayout::kRotations})
    if (name == channel_layout_name(layout)) return layout;
  throw InputError("expected a channel layout as-source or rotations, found '" + name + "'");
}

bool constant_offsets_below_root(const Clip& clip, double tolerance) {
  return plan_rotations(clip, tolerance).changing < 0;
}

ChannelLayout default_channel_layout(const Clip& source) {
  return constant_offsets_below_root(source) ? ChannelLayout::kRotations : ChannelLayout::kAsSource;
}

Clip with_rotation_channels(const Clip& clip, double tolerance) {
  const RotationsPlan plan = plan_rotations(clip, tolerance);
  const std::vector<Joint>& joints = clip.skeleton.joints;
  if (plan.changing >= 0) {
    const Joint& joint = joints[plan.changing];
    const Channel channel = joint.channels[plan.change.channel];
    const int column = joint.first_channel + plan.change.channel;
    std::string why;
    if (plan.trajectory_child >= 0 && joints[joint.parent].parent < 0)
      why = " (the trajectory is already on '" + joints[plan.trajectory_child].name + "')";
    // Frames are counted from 1, as the BVH reader's messages count them.
    throw InputError(clip.source + ": joint '" + joint.name + "' has position channels that change (" +
                     channel_name(channel) + " is " + format_number(clip.motion(0, column)) + " in frame 1 and " +
                     format_number(clip.motion(plan.change.frame, column)) + " in frame " +
                     std::to_string(plan.change.frame + 1) + "), which the rotations channel layout cannot hold" +
                     why + "; keep the source's layout (as-source)");
  }

  Clip out;
  out.source = clip.source;
  out.frame_time = clip.frame_time;
  out.skeleton = clip.skeleton;
  std::vector<int> columns;  // the source column of each output column
  columns.reserve(static_cast<size_t>(clip.skeleton.channel_count));
  int count = 0;
  for (size_t j = 0; j < joints.size(); ++j) {
    const Joint& from = joints[j];
    Joint& joint = out.skeleton.joints[j];
    const bool trajectory_child = static_cast<int>(j) == plan.trajectory_child;
    const bool keeps_positions = from.parent < 0 || trajectory_child;
    if (trajectory_child) {
      // Its channels place it whatever the OFFSET (Blender, our FK); readers that add the OFFSET
      // then read the same only with a zero one.
      joint.offset = Eigen::Vector3d::Zero();
    } else if (!keeps_positions && has_position_channel(from) && clip.frames() > 0) {
      // Blender's reading (kinematics.h joint_local_translation): the channels replace the whole OFFSET, a missing axis
      // reading 0. They keep one value, so frame 0's is every frame's.
      joint.offset = joint_local_translation(from, clip.motion.row(0).data());
    }
    joint.channels.clear();
    for (size_t c = 0; c < from.channels.size(); ++c) {
      if (!keeps_positions && is_position(from.channels[c])) continue;
      joint.channels.push_back(from.channels[c]);
      columns.push_back(from.first_channel + static_cast<int>(c));
    }
    joint.first_channel = count;
    count += static_cast<int>(joint.channels.size());
  }
  out.skeleton.channel_count = count;
  out.motion.resize(clip.motion.rows(), count);
  for (Eigen::Index f = 0; f < clip.motion.rows(); ++f)
    for (int c = 0; c < count; ++c) out.motion(f, c) = clip.motion(f, columns[c]);
  return out;
}

}  // namespace mostyle
