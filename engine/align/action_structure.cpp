#include "engine/align/action_structure.h"

#include <algorithm>
#include <cmath>

#include "engine/base/error.h"

namespace mostyle {
namespace {

// The take's fast speed is read at this percentile of its frames, so a single glitch does not set
// the scale and an action that fills most of a short take still does.
constexpr double kFastPercentile = 0.95;

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  const size_t at = std::min(v.size() - 1, static_cast<size_t>(std::floor(p * double(v.size() - 1) + 0.5)));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(at), v.end());
  return v[at];
}

// F: the fastest joint's speed at each frame (leg lengths per second), from the differences to
// the frames either side, then averaged over a window of `half` frames each side.
std::vector<double> smoothed_speed(const Eigen::MatrixXd& local, double fps, double leg_length, int half) {
  const Eigen::Index frames = local.rows(), joints = local.cols() / 3;
  std::vector<double> step(static_cast<size_t>(std::max<Eigen::Index>(frames - 1, 0)), 0.0);
  for (Eigen::Index f = 0; f + 1 < frames; ++f) {
    double fastest = 0.0;
    for (Eigen::Index j = 0; j < joints; ++j)
      fastest = std::max(fastest, (local.block(f + 1, 3 * j, 1, 3) - local.block(f, 3 * j, 1, 3)).squaredNorm());
    step[static_cast<size_t>(f)] = std::sqrt(fastest) * fps / leg_length;
  }
  std::vector<double> speed(static_cast<size_t>(frames), 0.0);
  if (step.empty()) return speed;
  for (Eigen::Index f = 0; f < frames; ++f) {
    const Eigen::Index lo = std::max<Eigen::Index>(0, f - 1 - half), hi = std::min<Eigen::Index>(frames - 2, f + half);
    double sum = 0.0;
    for (Eigen::Index s = lo; s <= hi; ++s) sum += step[static_cast<size_t>(s)];
    speed[static_cast<size_t>(f)] = sum / double(hi - lo + 1);
  }
  return speed;
}

// The spans where `moving` holds, a gap shorter than `bridge` frames closed, a span shorter than
// `shortest` dropped.
std::vector<FrameSpan> moving_spans(const std::vector<bool>& moving, int bridge, int shortest) {
  std::vector<FrameSpan> spans;
  const int frames = static_cast<int>(moving.size());
  for (int f = 0; f < frames;) {
    if (!moving[static_cast<size_t>(f)]) {
      ++f;
      continue;
    }
    int end = f;
    while (end < frames && moving[static_cast<size_t>(end)]) ++end;
    if (!spans.empty() && f - spans.back().end < bridge) spans.back().end = end;
    else spans.push_back({f, end});
    f = end;
  }
  spans.erase(std::remove_if(spans.begin(), spans.end(), [&](const FrameSpan& s) { return s.frames() < shortest; }),
              spans.end());
  return spans;
}

// Row: the mean pose over frames [begin, end) of local.
Eigen::RowVectorXd mean_pose(const Eigen::MatrixXd& local, int begin, int end) {
  return local.middleRows(begin, std::max(end - begin, 1)).colwise().mean();
}

// The farthest any joint is between two poses (rows of 3M), in leg lengths.
double pose_distance(const Eigen::RowVectorXd& a, const Eigen::RowVectorXd& b, double leg_length) {
  double farthest = 0.0;
  for (Eigen::Index j = 0; j < a.size() / 3; ++j) farthest = std::max(farthest, (a.segment(3 * j, 3) - b.segment(3 * j, 3)).norm());
  return farthest / leg_length;
}

// The moving spans joined across every pause but those held in a rest pose: a hand held up
// between raising and lowering it is part of one action, a return to standing between two kicks
// parts them. The rest poses are those before the first span and after the last, or the take's
// first and last frames where it starts or ends moving.
std::vector<FrameSpan> parted_at_rest(const Eigen::MatrixXd& local, const std::vector<FrameSpan>& spans,
                                      double leg_length, const ActionSpanOptions& o) {
  const int frames = static_cast<int>(local.rows());
  const Eigen::RowVectorXd before = spans.front().begin > 0 ? mean_pose(local, 0, spans.front().begin) : local.row(0);
  const Eigen::RowVectorXd after =
      spans.back().end < frames ? mean_pose(local, spans.back().end, frames) : local.row(frames - 1);
  std::vector<FrameSpan> out{spans.front()};
  for (size_t k = 1; k < spans.size(); ++k) {
    const Eigen::RowVectorXd pause = mean_pose(local, spans[k - 1].end, spans[k].begin);
    const bool at_rest = std::min(pose_distance(pause, before, leg_length), pose_distance(pause, after, leg_length)) <=
                         o.rest_pose_distance;
    if (at_rest) out.push_back(spans[k]);
    else out.back().end = spans[k].end;
  }
  return out;
}

// The column whose joint travels furthest against the body over the span.
int most_moving_joint(const Eigen::MatrixXd& local, const FrameSpan& span) {
  int best = -1;
  double longest = -1.0;
  for (Eigen::Index j = 0; j < local.cols() / 3; ++j) {
    double path = 0.0;
    for (int f = span.begin; f + 1 < span.end; ++f)
      path += (local.block(f + 1, 3 * j, 1, 3) - local.block(f, 3 * j, 1, 3)).norm();
    if (path > longest) {
      longest = path;
      best = static_cast<int>(j);
    }
  }
  return best;
}

}  // namespace

void ActionSpanOptions::Validate() const {
  for (double v : {smoothing_s, rest_share, still_speed, moving_speed, min_rest_s, min_pause_s, min_action_s, rest_pose_distance})
    if (!(v > 0.0) || !std::isfinite(v))
      throw InputError("action structure: every threshold (speeds, shares, durations) must be a number above 0");
}

ActionSpans find_action_spans(const Eigen::MatrixXd& local, double fps, double leg_length,
                              const ActionSpanOptions& o) {
  o.Validate();
  if (!(fps > 0.0) || !(leg_length > 0.0))
    throw InputError("action structure: the frame rate and the leg length must be above 0");
  ActionSpans out;
  out.frames = static_cast<int>(local.rows());
  out.rest_before = out.frames;
  if (out.frames < 2 || local.cols() < 3) return out;
  const int half = std::max(1, static_cast<int>(std::lround(0.5 * o.smoothing_s * fps)));
  const std::vector<double> speed = smoothed_speed(local, fps, leg_length, half);
  const double fast = percentile(speed, kFastPercentile);
  if (fast < o.moving_speed) return out;  // at rest throughout
  const double threshold = std::max(o.rest_share * fast, o.still_speed);
  std::vector<bool> moving(speed.size());
  for (size_t f = 0; f < speed.size(); ++f) moving[f] = speed[f] > threshold;
  auto frames_of = [&](double s) { return std::max(1, static_cast<int>(std::lround(s * fps))); };
  out.actions = moving_spans(moving, frames_of(o.min_pause_s), frames_of(o.min_action_s));
  if (out.actions.empty()) return out;
  out.actions = parted_at_rest(local, out.actions, leg_length, o);
  // A rest at an end too short to be one is the action's start or end.
  if (out.actions.front().begin < frames_of(o.min_rest_s)) out.actions.front().begin = 0;
  if (out.frames - out.actions.back().end < frames_of(o.min_rest_s)) out.actions.back().end = out.frames;
  out.rest_before = out.actions.front().begin;
  out.rest_after = out.frames - out.actions.back().end;
  out.mover = most_moving_joint(local, out.active());
  return out;
}

std::string body_part_of(const std::string& name) {
  const std::string side = name.rfind("left", 0) == 0 ? "left " : name.rfind("right", 0) == 0 ? "right " : "";
  auto has = [&](const char* part) { return name.find(part) != std::string::npos; };
  if (has("wrist") || has("hand")) return side + "hand";
  if (has("elbow") || has("shoulder")) return side + "arm";
  if (has("ankle") || has("toe")) return side + "foot";
  if (has("knee") || (has("hip") && !side.empty())) return side + "leg";
  if (has("head")) return "head";
  return "body";
}

}  // namespace mostyle
