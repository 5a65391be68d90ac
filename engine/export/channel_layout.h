#pragma once
// Channel layout of an exported BVH file, so that every reader places the joints alike.
//
// Readers disagree on position channels below the root. Blender (and our FK,
// kinematics.h joint_local_translation) let a joint's position channels REPLACE its OFFSET, an
// axis without a channel reading 0; three.js's BVHLoader and other game-side readers ADD them to
// the OFFSET. On a file with position channels on every joint (Bandai) the latter read every bone
// twice as long and the hips an OFFSET too high: more than a skeleton's height off. A joint
// without position channels is read alike by all (its OFFSET), and so is one whose OFFSET is 0.
//
// The rotations layout keeps position channels only where the trajectory is: on the root, and on
// one child of the root whose position channels change (the "trajectory child": Bandai's Hips
// below the still ROOT joint_Root). Every other joint's position channels must keep one value;
// they are folded into its OFFSET (Blender's reading of them) and dropped. The trajectory child's
// OFFSET becomes 0 (format_bvh writes a root's OFFSET as 0 for the same reason), so its channels
// place it in every reader; its rest position is then its parent's.
#include <string>

#include "engine/base/clip.h"

namespace mostyle {

enum class ChannelLayout {
  kAsSource,   // the source take's channels, joint by joint (Bandai: 6 on every joint)
  kRotations,  // position channels only on the root and the trajectory child (see above)
};

// "as-source" or "rotations": the names the CLI's --channels takes.
const char* channel_layout_name(ChannelLayout layout);

// The layout named `name` (channel_layout_name's spelling, exact). Throws InputError with a
// sentence naming the choices on any other name.
ChannelLayout parse_channel_layout(const std::string& name);

// Tolerance of "keeps one value": a position channel is constant when every frame's value is
// within this fraction of the clip's size of frame 0's value. The size is the largest length
// among the joints' OFFSETs and their frame-0 local translations (our FK), 1 when all are 0.
// The real Bandai files vary by 1e-11 cm on channels that mean one value.
constexpr double kConstantChannelTolerance = 1e-6;

// True when the clip fits the rotations layout: every joint's position channels keep one value
// over all frames (within `tolerance`, relative, see kConstantChannelTolerance), except the
// root's and the trajectory child's. True for a clip without position channels below the root
// (CMU) and for one without frames. O(frames x channels).
bool constant_offsets_below_root(const Clip& clip, double tolerance = kConstantChannelTolerance);

// The layout an export takes when the user does not choose: kRotations when
// constant_offsets_below_root(source), else kAsSource (changing position channels below the
// root, stretching bones, are kept as the source has them). O(frames x channels).
ChannelLayout default_channel_layout(const Clip& source);

// The clip in the rotations layout: the same motion by our FK (and Blender's), and by readers
// that add position channels to the OFFSET too. Every joint other than the root and the
// trajectory child loses its position channels, and its OFFSET becomes what they gave at
// frame 0 (all three axes: an axis without a channel becomes 0, as our FK and Blender read it;
// with no frames the OFFSET stays). The trajectory child keeps its channels and gets OFFSET 0.
// Remaining channels keep their order (so each joint's rotation order), motion columns follow,
// first_channel and channel_count are renumbered; source, frame time and frames are kept.
// Throws InputError naming the joint (and the frame where it first changes) when a position
// channel that would be folded does not keep one value. O(frames x channels); allocates the copy.
Clip with_rotation_channels(const Clip& clip, double tolerance = kConstantChannelTolerance);

}  // namespace mostyle
