#pragma once
// The structure of one take's action: rest, action, rest. Animators' takes of a bow, a wave or a
// kick start and end standing still; between the still poses the body moves, once (a one-shot
// stroke) or in repeated strokes (each wave of a hand). Walks are the special case whose strokes
// are gait cycles (cycles.h). The rests and the moving span are what registration matches
// between takes that do not walk: rest to rest, action to action.
//
// Still is judged against the take's own motion: a frame rests where its fastest joint (in the
// canonical frame, the travel taken out) moves less than a share of the take's typical fast
// speed, and less than an absolute floor counts as still whatever the take does.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace mostyle {

struct FrameSpan {
  int begin = 0, end = 0;  // frames [begin, end)
  int frames() const { return end - begin; }
};

struct ActionSpanOptions {
  double smoothing_s = 0.15;  // the joints' speed is averaged over this window before it is judged
  double rest_share = 0.12;   // of the take's fast speed (its 95th percentile): slower is at rest
  double still_speed = 0.05;  // leg lengths per second: slower is at rest in any take
  double moving_speed = 0.3;  // leg lengths per second: a take never faster than this rests throughout
  double min_rest_s = 0.2;    // a rest at either end lasts at least this long, else the action runs to the end
  double min_pause_s = 0.4;   // a rest inside the moving span this long parts two actions
  double min_action_s = 0.15; // movement shorter than this between rests is a twitch, part of the rest
  // Leg lengths: a pause parts two actions only where every joint is within this of a rest pose
  // (a hand held up between raising and lowering it is part of one action).
  double rest_pose_distance = 0.2;
  void Validate() const;      // throws InputError on a value that is not a positive number
};

// A take read as rest, actions and rest. frames: the take's length. Frames [0, rest_before) rest
// before the first action, [frames - rest_after, frames) after the last; the actions lie between,
// parted by pauses. A take at rest throughout has no actions and rest_before = frames.
struct ActionSpans {
  int frames = 0;
  int rest_before = 0, rest_after = 0;
  std::vector<FrameSpan> actions;  // in order, inside [rest_before, frames - rest_after)
  // The column (joint index in the canonical poses) that moves most within the actions; -1 at rest.
  int mover = -1;
  // That joint's body part in words ("left hand", body_part_of), named by the caller that knows
  // which joint each column is; empty when not named.
  std::string mover_part;
  bool still() const { return actions.empty(); }
  // The moving span: from the first action's start to the last one's end; empty when still.
  FrameSpan active() const {
    return still() ? FrameSpan{frames, frames} : FrameSpan{actions.front().begin, actions.back().end};
  }
  bool rests_at_both_ends() const { return rest_before > 0 && rest_after > 0; }
};

// The rests and actions of one take. local: F x 3M canonical joint positions (canonical_frame.h),
// fps their rate, leg_length what speeds are judged in (the same units). Throws InputError on
// fps or leg_length not above 0, or bad options. O(F x M).
ActionSpans find_action_spans(const Eigen::MatrixXd& local, double fps, double leg_length,
                              const ActionSpanOptions& options = {});

// What a body part is called in a structure's words, from a canonical joint's name
// (major_skeleton.h major_joint_name): "left_wrist" -> "left hand", "right_ankle" -> "right foot",
// "head" -> "head", the trunk's joints -> "body".
std::string body_part_of(const std::string& major_joint_name);

}  // namespace mostyle
