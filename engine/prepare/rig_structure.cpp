#include "engine/prepare/rig_structure.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>

#include "engine/kinematics/kinematics.h"

namespace mostyle {
namespace {

// Lengths and heights are fractions of the rest pose's height (its vertical extent).
constexpr double kLegsLevel = 0.25;      // the legs' lowest points lie within this of each other (a foot in the air)
constexpr double kMinHipsHeight = 0.05;  // the hips stand at least this high above the lowest joint
// Of the hips' height above the lowest joint: how far down the legs go. One reaches the floor (a
// robot's or a cartoon's legs are short, but they are what it stands on), the other at least
// down to where a knee would be (a foot in the air). Arms hanging by the sides end well above
// the floor. Only where no pair reaches the floor do legs that end at the knees count (an IK
// rig whose feet hang from the root).
constexpr double kFloorReach = 0.9;
constexpr double kKneeReach = 0.4;
constexpr double kMinFeetApart = 0.04;   // the legs' lowest points lie at least this far apart
constexpr double kMaxLegRatio = 1.5;     // the longer leg is at most this times the shorter
constexpr double kMinLimbReach = 0.15;   // a leg or an arm reaches at least this far
constexpr double kMinLongBone = 0.05;    // a thigh, shin, upper arm or forearm is at least this long
constexpr double kMinSpineRise = 0.1;    // the spine's top stands at least this above the hips
constexpr double kMinSideways = 0.02;    // an arm lies at least this far to its side of the spine
constexpr double kMinApart = 0.02;       // the legs lie at least this far apart to tell a side
constexpr double kMinCue = 0.01;         // a facing cue counts from this much forward
constexpr double kCueShare = 0.25;       // ... and when its sum is this share of its parts' sizes
// Of the shin's length: how near its end an IK rig's ankle lies.
constexpr double kIkReach = 0.35;
// The most frames the motion cues read (evenly spaced).
constexpr int kCueFrames = 240;

const Eigen::Vector3d kUp = Eigen::Vector3d::UnitY();

Eigen::Vector3d horizontal(const Eigen::Vector3d& v) { return Eigen::Vector3d(v.x(), 0.0, v.z()); }

// The skeleton as a tree over its rest pose.
struct Tree {
  const Skeleton& s;
  std::vector<Eigen::Vector3d> p;          // rest positions
  std::vector<std::vector<int>> children;  // End Sites included
  std::vector<double> reach;               // the longest way down to a leaf (sum of bone lengths)
  std::vector<int> next;                   // the child on that way, -1 at a leaf
  std::vector<double> low, high;           // lowest and highest y in the subtree
  std::vector<int> lowest;                 // the subtree's lowest joint
  std::vector<char> marker;                // a leaf the motion never moves: an end marker
  double floor = 0.0, height = 0.0;

  // positions: per joint, the pose to read (the rest pose, or a frame's).
  Tree(const Skeleton& skeleton, std::vector<Eigen::Vector3d> positions) : s(skeleton), p(std::move(positions)) {
    const int n = size();
    children.resize(n);
    for (int j = 0; j < n; ++j)
      if (s.joints[j].parent >= 0) children[s.joints[j].parent].push_back(j);
    reach.assign(n, 0.0);
    next.assign(n, -1);
    low.resize(n);
    high.resize(n);
    lowest.resize(n);
    marker.assign(n, 0);
    for (int j = n - 1; j >= 0; --j) {  // children come after their parents
      low[j] = high[j] = p[j].y();
      lowest[j] = j;
      for (int c : children[j]) {
        const double r = (p[c] - p[j]).norm() + reach[c];
        if (next[j] < 0 || r > reach[j]) {
          reach[j] = r;
          next[j] = c;
        }
        if (low[c] < low[j]) {
          low[j] = low[c];
          lowest[j] = lowest[c];
        }
        high[j] = std::max(high[j], high[c]);
      }
    }
    if (n > 0) {
      floor = low[0];
      double top = high[0];
      for (int j = 0; j < n; ++j) {
        if (s.joints[j].parent >= 0) continue;
        floor = std::min(floor, low[j]);
        top = std::max(top, high[j]);
      }
      height = top - floor;
    }
  }
  int size() const { return static_cast<int>(s.joints.size()); }
  bool real(int j) const { return j >= 0 && !s.joints[j].end_site; }
  int parent(int j) const { return s.joints[j].parent; }
  bool is_ancestor(int a, int j) const {
    for (int up = parent(j); up >= 0; up = parent(up))
      if (up == a) return true;
    return false;
  }
  bool in_subtree(int j, int top) const { return j == top || is_ancestor(top, j); }
  // The way down from j along the longest reach, j first.
  std::vector<int> chain(int j) const {
    std::vector<int> out;
    for (; j >= 0; j = next[j]) out.push_back(j);
    return out;
  }
  double bone(int a, int b) const { return (p[b] - p[a]).norm(); }
};

void find_markers(Tree& t, const MotionMatrix& motion) {
  if (motion.rows() < 2) return;
  for (int j = 0; j < t.size(); ++j) {
    const Joint& joint = t.s.joints[j];
    // A BVH's leaf joint ends in an End Site, which is its marker: only a joint with no child at
    // all (FBX's and glTF's "_End" nodes) can be one.
    if (!t.real(j) || !t.children[j].empty()) continue;
    bool still = true;
    for (size_t c = 0; c < joint.channels.size() && still; ++c) {
      const auto column = motion.col(joint.first_channel + static_cast<int>(c));
      still = column.maxCoeff() - column.minCoeff() <= 1e-9;
    }
    t.marker[j] = still ? 1 : 0;
  }
}

// A leg or an arm cut at its two longest consecutive bones.
struct Limb {
  int root = -1;                 // the chain's first joint (a child of the hips or the chest)
  std::vector<int> chain;        // root down along the longest reach
  int upper = -1, middle = -1;   // hip and knee, or shoulder and elbow
  int end = -1, tip = -1;        // ankle and toe, or wrist and hand
  int end_point = -1;            // the chain's joint after the middle one (an End Site too), -1: none
  bool ik = false;               // the end is the joint nearest the shin's end, not under the knee
};

// The joint after a limb's end (the toe after the ankle, the hand after the wrist), passing over
// joints at the end's own place: on a foot, the one whose chain reaches farthest; on a hand
// (`straight`), the one that goes on most nearly along the forearm (the middle finger, not the
// thumb), among those that reach at least half as far as the farthest.
int tip_after(const Tree& t, int end, const Eigen::Vector3d& along, bool straight) {
  const double zero = 1e-3 * t.height;
  std::vector<int> candidates, open{end};
  while (!open.empty()) {
    const int j = open.back();
    open.pop_back();
    for (int c : t.children[j]) {
      if (!t.real(c)) continue;
      if (t.bone(end, c) <= zero) open.push_back(c);
      else candidates.push_back(c);
    }
  }
  int best = -1;
  double farthest = 0.0;
  for (int c : candidates) farthest = std::max(farthest, t.bone(end, c) + t.reach[c]);
  double best_score = -std::numeric_limits<double>::infinity();
  for (int c : candidates) {
    const double reach = t.bone(end, c) + t.reach[c];
    double score = reach;
    if (straight) {
      if (reach < 0.5 * farthest) continue;
      const double norm = along.norm();
      score = norm > 0 ? (t.p[c] - t.p[end]).normalized().dot(along / norm) : 0.0;
    }
    if (score > best_score) {
      best_score = score;
      best = c;
    }
  }
  return best;
}

Limb cut_limb(const Tree& t, int root, bool arm) {
  Limb limb;
  limb.root = root;
  limb.chain = t.chain(root);
  const std::vector<int>& c = limb.chain;
  const double long_bone = kMinLongBone * t.height;
  // The two longest consecutive bones: thigh and shin, upper arm and forearm.
  int best = -1;
  double best_length = long_bone;
  for (size_t i = 0; i + 2 < c.size(); ++i) {
    const double shorter = std::min(t.bone(c[i], c[i + 1]), t.bone(c[i + 1], c[i + 2]));
    if (shorter >= best_length) {
      best_length = shorter;
      best = static_cast<int>(i);
    }
  }
  if (best < 0) {
    // One long bone only (a chain that ends at the knee or the elbow).
    double longest = long_bone;
    for (size_t i = 0; i + 1 < c.size(); ++i) {
      if (t.bone(c[i], c[i + 1]) >= longest && t.real(c[i + 1])) {
        longest = t.bone(c[i], c[i + 1]);
        best = static_cast<int>(i);
      }
    }
    if (best < 0 || !t.real(c[best])) return limb;
    limb.upper = c[best];
    limb.middle = c[best + 1];
    return limb;
  }
  if (!t.real(c[best]) || !t.real(c[best + 1])) return limb;
  limb.upper = c[best];
  limb.middle = c[best + 1];
  limb.end_point = c[best + 2];
  if (t.real(c[best + 2])) {
    limb.end = c[best + 2];
    limb.tip = tip_after(t, limb.end, t.p[limb.end] - t.p[limb.middle], arm);
  }
  return limb;
}

// The joint at the shin's end of a leg whose foot does not hang from the shin (an IK rig): the
// joint nearest the shin's end (the chain's End Site, or one shin's length on from the knee
// along the thigh), within kIkReach of the shin's length, among those `taken` leaves free.
void find_ik_ankle(const Tree& t, Limb& leg, const std::vector<char>& taken) {
  if (leg.middle < 0 || leg.end >= 0) return;
  Eigen::Vector3d shin_end;
  if (leg.end_point >= 0) {
    shin_end = t.p[leg.end_point];
  } else {
    const Eigen::Vector3d thigh = t.p[leg.middle] - t.p[leg.upper];
    shin_end = t.p[leg.middle] + thigh;
  }
  const double shin = (shin_end - t.p[leg.middle]).norm();
  if (!(shin > 0)) return;
  int best = -1;
  double best_distance = kIkReach * shin;
  for (int j = 0; j < t.size(); ++j) {
    if (!t.real(j) || taken[j]) continue;
    const double d = (t.p[j] - shin_end).norm();
    // Nearer wins; at one place, a joint with a foot below it.
    if (d < best_distance || (best >= 0 && d == best_distance && t.children[best].empty() && !t.children[j].empty())) {
      best_distance = d;
      best = j;
    }
  }
  if (best < 0) return;
  leg.end = best;
  leg.ik = true;
  leg.tip = tip_after(t, best, t.p[best] - t.p[leg.middle], false);
}

// The hips and the roots of its two legs: of the pairs of chains that leave one joint standing
// above the floor and go down from it, one at least `reach` of the way to the floor, apart sideways
// and of a like length, the pair that stands most like two legs under the body: its lowest
// points lowest, and placed on either side of the joint (their midpoint under it), so a tail on
// the floor behind a cartoon is no leg. Proportions are not a human's: a robot's legs may be a
// fifth of its height and its arms hang lower than its hips stand.
bool find_legs_reaching(const Tree& t, double reach, int* hips, int* root_a, int* root_b) {
  double best = std::numeric_limits<double>::infinity();
  for (int x = 0; x < t.size(); ++x) {
    const double above = t.p[x].y() - t.floor;
    if (!t.real(x) || above < kMinHipsHeight * t.height) continue;
    const auto reach_down = [&](int c) { return (t.p[x].y() - t.low[c]) / above; };
    const std::vector<int>& children = t.children[x];
    for (size_t i = 0; i < children.size(); ++i) {
      const int c = children[i];
      if (!t.real(c) || reach_down(c) < kKneeReach) continue;
      for (size_t k = i + 1; k < children.size(); ++k) {
        const int d = children[k];
        if (!t.real(d) || reach_down(d) < kKneeReach) continue;
        if (std::max(reach_down(c), reach_down(d)) < reach) continue;
        if (std::abs(t.low[c] - t.low[d]) > kLegsLevel * t.height) continue;
        const Eigen::Vector3d foot_c = t.p[t.lowest[c]], foot_d = t.p[t.lowest[d]];
        if (horizontal(foot_c - foot_d).norm() < kMinFeetApart * t.height) continue;
        const double reach_c = t.bone(x, c) + t.reach[c], reach_d = t.bone(x, d) + t.reach[d];
        if (std::max(reach_c, reach_d) > kMaxLegRatio * std::min(reach_c, reach_d)) continue;
        // Both terms are lengths: how far the higher foot is off the floor, and how far the feet's
        // midpoint lies from under the joint they hang from.
        const double off_floor = std::max(t.low[c], t.low[d]) - t.floor;
        const double off_centre = horizontal(0.5 * (foot_c + foot_d) - t.p[x]).norm();
        if (off_floor + off_centre < best) {
          best = off_floor + off_centre;
          *hips = x;
          *root_a = c;
          *root_b = d;
        }
      }
    }
  }
  return best < std::numeric_limits<double>::infinity();
}

bool find_legs(const Tree& t, int* hips, int* root_a, int* root_b) {
  return find_legs_reaching(t, kFloorReach, hips, root_a, root_b) ||
         find_legs_reaching(t, kKneeReach, hips, root_a, root_b);
}

// The way up from the hips: the hips' other child whose subtree stands highest (or, when the
// legs are all the hips holds, such a child of a joint above the hips), then on along the child
// that stands highest. Returns the joints from the first above the base; *base: where it leaves.
std::vector<int> find_spine(const Tree& t, int hips, int leg_a, int leg_b, int* base) {
  const double rise = t.p[hips].y() + kMinSpineRise * t.height;
  int first = -1;
  *base = hips;
  for (int x = hips, from = -1; x >= 0 && first < 0; from = x, x = t.parent(x)) {
    for (int d : t.children[x]) {
      if (d == from || d == leg_a || d == leg_b || !t.real(d) || t.high[d] < rise) continue;
      if (first < 0 || t.high[d] > t.high[first]) first = d;
    }
    if (first >= 0) *base = x;
  }
  std::vector<int> spine;
  for (int j = first; j >= 0;) {
    spine.push_back(j);
    int up = -1;
    for (int c : t.children[j])
      if (t.real(c) && (up < 0 || t.high[c] > t.high[up])) up = c;
    j = up;
  }
  return spine;
}

// Side of a chain: the mean of its joints, from `from`, along `lateral`.
double chain_side(const Tree& t, const std::vector<int>& chain, int from, const Eigen::Vector3d& lateral) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (int j : chain) mean += t.p[j];
  mean /= static_cast<double>(chain.size());
  return (mean - t.p[from]).dot(lateral);
}

// Positions of every joint at up to kCueFrames frames of the motion, evenly spaced, each followed
// by the frame after it (the last frame by itself): 2 x frames poses of every joint.
std::vector<std::vector<Eigen::Vector3d>> sample_positions(const Skeleton& s, const MotionMatrix& motion) {
  const Eigen::Index frames = motion.rows();
  const Eigen::Index count = std::min<Eigen::Index>(frames, kCueFrames);
  std::vector<std::vector<Eigen::Vector3d>> out;
  Pose pose;
  for (Eigen::Index k = 0; k < 2 * count; ++k) {
    const Eigen::Index first = count > 1 ? (k / 2) * (frames - 1) / (count - 1) : 0;
    const Eigen::Index f = std::min(first + k % 2, frames - 1);
    pose_frame(s, motion.row(f).data(), &pose);
    out.push_back(pose.positions);
  }
  return out;
}

// A facing cue summed over legs and poses: how far forward (as one hypothesis of the facing
// has it) and how large its parts are.
struct Cue {
  double sum = 0.0, size = 0.0;
  void add(double along, double magnitude) {
    sum += along;
    size += magnitude;
  }
  // +1 or -1 when the cue is clear, else 0.
  int sign(double min_size) const {
    if (size < min_size || std::abs(sum) < kCueShare * size) return 0;
    return sum > 0 ? 1 : -1;
  }
};

// Forward of a pose if leg a is the left one, from the legs' hips: left = up x forward.
Eigen::Vector3d forward_if_a_left(const std::vector<Eigen::Vector3d>& p, const Limb& a, const Limb& b) {
  const Eigen::Vector3d lateral = horizontal(p[a.upper] - p[b.upper]);
  const double norm = lateral.norm();
  if (!(norm > 0)) return Eigen::Vector3d::Zero();
  return (lateral / norm).cross(kUp);
}

void add_toes(Cue& cue, const std::vector<Eigen::Vector3d>& p, const Limb& leg, const Eigen::Vector3d& forward) {
  if (leg.end < 0) return;
  int end = leg.tip;
  if (end < 0 && !leg.ik) {
    // The point after the ankle along the chain: the toe, or the End Site at the foot's end.
    const auto at = std::find(leg.chain.begin(), leg.chain.end(), leg.end);
    if (at != leg.chain.end() && at + 1 != leg.chain.end()) end = *(at + 1);
  }
  if (end < 0) return;
  const Eigen::Vector3d foot = horizontal(p[end] - p[leg.end]);
  cue.add(foot.dot(forward), foot.norm());
}

void add_knee(Cue& cue, const std::vector<Eigen::Vector3d>& p, const Limb& leg, const Eigen::Vector3d& forward) {
  if (leg.end < 0 || leg.middle < 0) return;
  const Eigen::Vector3d a = p[leg.upper], b = p[leg.end], k = p[leg.middle];
  const Eigen::Vector3d ab = b - a;
  const double len2 = ab.squaredNorm();
  if (!(len2 > 0)) return;
  const double s = std::clamp((k - a).dot(ab) / len2, 0.0, 1.0);
  const Eigen::Vector3d bend = horizontal(k - (a + s * ab));
  cue.add(bend.dot(forward), bend.norm());
}

std::string quoted(const Skeleton& s, int j) { return "'" + s.joints[j].name + "'"; }

// What the structure finds, step by step.
struct Body {
  int hips = -1, root_a = -1, root_b = -1;  // the hips and its legs' first joints
  Limb leg_a, leg_b, arm_a, arm_b;          // arm_a on leg a's side
  int spine_base = -1;                      // the joint the spine leaves (the hips, or above them)
  std::vector<int> spine;                   // up from spine_base to the highest joint
  Eigen::Vector3d lateral = Eigen::Vector3d::Zero();  // towards leg a, level, unit when sides_apart
  bool sides_apart = false;
  int chest_at = -1;                        // index in spine of the joint the arms leave
  int head = -1, lower_spine = -1;
  bool legs_cut() const { return leg_a.upper >= 0 && leg_b.upper >= 0 && leg_a.middle >= 0 && leg_b.middle >= 0; }
};

// Which leg is the left one by the body's facing: +1 leg a, -1 leg b, 0 when nothing tells. The
// first cue that tells wins, in this order: the toes and the knees' bend in the rest pose (when
// t holds the rest pose); over
// the motion, the knees' bend (knees bend forward), the planted foot's slide under the body (it
// moves backward), the root's travel, the toes (least sure: a pointed foot's toe trails the
// ankle). *contradicted: another of those cues (the motion's toes aside) tells the other way.
int facing_from_body(const Skeleton& skeleton, const Tree& t, const MotionMatrix* motion, const Body& b,
                     bool rest_pose, FacingCue* cue, bool* contradicted) {
  const Limb& leg_a = b.leg_a;
  const Limb& leg_b = b.leg_b;
  const int hips = b.hips;
  const double min_size = kMinCue * t.height;
  std::vector<std::pair<FacingCue, int>> told;
  // A frame's pose is no rest pose: a walk's trailing foot points back. Its cues are the motion's.
  if (rest_pose) {
    const Eigen::Vector3d forward = forward_if_a_left(t.p, leg_a, leg_b);
    Cue toes, knees;
    for (const Limb* leg : {&leg_a, &leg_b}) {
      add_toes(toes, t.p, *leg, forward);
      add_knee(knees, t.p, *leg, forward);
    }
    told.push_back({FacingCue::kRestToes, toes.sign(min_size)});
    told.push_back({FacingCue::kRestKnees, knees.sign(min_size)});
  }
  if (motion != nullptr && motion->rows() > 0) {
    const auto poses = sample_positions(skeleton, *motion);
    Cue toes, knees, slide, travel;
    for (size_t k = 0; k + 1 < poses.size(); k += 2) {
      const std::vector<Eigen::Vector3d>& p = poses[k];
      const std::vector<Eigen::Vector3d>& q = poses[k + 1];  // the next frame
      const Eigen::Vector3d f = forward_if_a_left(p, leg_a, leg_b);
      for (const Limb* leg : {&leg_a, &leg_b}) {
        add_toes(toes, p, *leg, f);
        add_knee(knees, p, *leg, f);
      }
      if (leg_a.end >= 0 && leg_b.end >= 0) {
        const int planted = p[leg_a.end].y() <= p[leg_b.end].y() ? leg_a.end : leg_b.end;
        const Eigen::Vector3d moved = horizontal((q[planted] - q[hips]) - (p[planted] - p[hips]));
        slide.add(-moved.dot(f), moved.norm());
      }
      const Eigen::Vector3d step = horizontal(q[hips] - p[hips]);
      travel.add(step.dot(f), step.norm());
    }
    const double frames = static_cast<double>(poses.size() / 2);
    told.push_back({FacingCue::kMotionKnees, knees.sign(min_size * frames)});
    told.push_back({FacingCue::kMotionSlide, slide.sign(min_size)});
    told.push_back({FacingCue::kTravel, travel.sign(kMinLimbReach * t.height)});
    told.push_back({FacingCue::kMotionToes, toes.sign(min_size * frames)});
  }
  int a_left = 0;
  *contradicted = false;
  for (const auto& [which, sign] : told) {
    if (sign == 0) continue;
    if (a_left == 0) {
      a_left = sign;
      *cue = which;
    } else if (sign != a_left && which != FacingCue::kMotionToes) {
      *contradicted = true;
    }
  }
  return a_left;
}

}  // namespace

const char* facing_cue_name(FacingCue cue) {
  switch (cue) {
    case FacingCue::kNone: return "nothing (+Z is taken as the facing)";
    case FacingCue::kNames: return "the joints' names";
    case FacingCue::kRestToes: return "the toes in the rest pose";
    case FacingCue::kRestKnees: return "the knees' bend in the rest pose";
    case FacingCue::kMotionToes: return "the toes over the motion";
    case FacingCue::kMotionKnees: return "the knees' bend over the motion";
    case FacingCue::kMotionSlide: return "the planted foot's slide over the motion";
    case FacingCue::kTravel: return "the root's travel";
  }
  return "?";
}

namespace {

// The level direction from leg b to leg a (their hips, else their lowest joints).
void find_sides(const Tree& t, Body& b) {
  if (b.leg_a.upper >= 0 && b.leg_b.upper >= 0) b.lateral = horizontal(t.p[b.leg_a.upper] - t.p[b.leg_b.upper]);
  if (b.lateral.norm() < kMinApart * t.height)
    b.lateral = horizontal(t.p[t.lowest[b.root_a]] - t.p[t.lowest[b.root_b]]);
  b.sides_apart = b.lateral.norm() >= kMinApart * t.height;
  if (b.sides_apart) b.lateral.normalize();
}

// The arms: of the pairs of chains that leave one spine joint to either side, the pair that
// reaches farthest (at least kMinLimbReach); that joint is the chest.
void find_arms(const Tree& t, Body& b) {
  double best = kMinLimbReach * t.height;
  int arm_a = -1, arm_b = -1;
  for (size_t i = 0; i + 1 < b.spine.size() && b.sides_apart; ++i) {
    const int s = b.spine[i];
    for (int d1 : t.children[s]) {
      if (d1 == b.spine[i + 1] || !t.real(d1)) continue;
      if (chain_side(t, t.chain(d1), s, b.lateral) < kMinSideways * t.height) continue;  // d1 on leg a's side
      for (int d2 : t.children[s]) {
        if (d2 == b.spine[i + 1] || d2 == d1 || !t.real(d2)) continue;
        if (chain_side(t, t.chain(d2), s, b.lateral) > -kMinSideways * t.height) continue;
        const double reach = std::min(t.bone(s, d1) + t.reach[d1], t.bone(s, d2) + t.reach[d2]);
        if (reach >= best) {
          best = reach;
          b.chest_at = static_cast<int>(i);
          arm_a = d1;
          arm_b = d2;
        }
      }
    }
  }
  if (arm_a < 0) return;
  b.arm_a = cut_limb(t, arm_a, true);
  b.arm_b = cut_limb(t, arm_b, true);
  // A hand that is an end marker is no hand.
  for (Limb* arm : {&b.arm_a, &b.arm_b})
    if (arm->tip >= 0 && t.marker[arm->tip]) arm->tip = -1;
}

// The head: the last joint above the chest that is not an end marker. The lower spine: the joint
// nearest a third of the way (by length) from the hips to the chest (or the head).
void find_head_and_spine(const Tree& t, Body& b) {
  for (size_t i = static_cast<size_t>(b.chest_at >= 0 ? b.chest_at + 1 : 1); i < b.spine.size(); ++i)
    if (t.real(b.spine[i]) && !t.marker[b.spine[i]]) b.head = b.spine[i];
  const int top = b.chest_at >= 0 ? b.chest_at
                                  : static_cast<int>(std::find(b.spine.begin(), b.spine.end(), b.head) - b.spine.begin());
  const int count = std::min(top, static_cast<int>(b.spine.size()) - 1);
  double along = 0.0;
  std::vector<double> at;
  for (int i = 0; i <= count; ++i) {
    along += t.bone(i == 0 ? b.spine_base : b.spine[i - 1], b.spine[i]);
    at.push_back(along);
  }
  int best = -1;
  for (int i = 0; i < top && i <= count; ++i) {
    if (at[i] <= 1e-6 * t.height || b.spine[i] == b.head) continue;
    if (best < 0 || std::abs(at[i] - along / 3) < std::abs(at[best] - along / 3)) best = i;
  }
  if (best >= 0) b.lower_spine = b.spine[best];
}

// IK ankles: for a leg whose shin has no foot under it, a joint not already part of the body.
void find_ik_ankles(const Tree& t, Body& b) {
  std::vector<char> taken(static_cast<size_t>(t.size()), 0);
  for (int up = b.hips; up >= 0; up = t.parent(up)) taken[up] = 1;
  for (const std::vector<int>* c : std::initializer_list<const std::vector<int>*>{
           &b.leg_a.chain, &b.leg_b.chain, &b.spine, &b.arm_a.chain, &b.arm_b.chain})
    for (int j : *c) taken[j] = 1;
  find_ik_ankle(t, b.leg_a, taken);
  if (b.leg_a.end >= 0) taken[b.leg_a.end] = 1;
  find_ik_ankle(t, b.leg_b, taken);
}

// Which leg is the left one (+1 leg a, -1 leg b): the body's facing where it tells, else the
// names, else +Z; 0 when the legs cannot be told apart. Sets out's facing and names_sides.
int tell_left(const Skeleton& skeleton, const Tree& t, bool rest_pose, const MotionMatrix* motion,
              const MajorMapping* named, const Body& b, RigStructure& out) {
  if (!b.sides_apart) return 0;
  int a_left = 0;
  bool contradicted = false;
  if (b.legs_cut())
    a_left = facing_from_body(skeleton, t, motion, b, rest_pose, &out.facing, &contradicted);
  int named_a_left = 0;
  if (named != nullptr) {
    int votes = 0;
    for (int major = static_cast<int>(MajorJoint::kLeftShoulder); major < kMajorJointCount; ++major) {
      const int j = named->joint[major];
      if (j < 0) continue;
      const bool left = (major >= 4 && major <= 7) || (major >= 12 && major <= 15);
      const bool on_a = t.in_subtree(j, b.root_a) || (b.arm_a.root >= 0 && t.in_subtree(j, b.arm_a.root));
      const bool on_b = t.in_subtree(j, b.root_b) || (b.arm_b.root >= 0 && t.in_subtree(j, b.arm_b.root));
      if (on_a != on_b) votes += (on_a == left) ? 1 : -1;
    }
    named_a_left = votes > 0 ? 1 : votes < 0 ? -1 : 0;
  }
  if (a_left != 0 && named_a_left != 0 && !contradicted) out.names_sides = a_left == named_a_left ? 1 : -1;
  if (a_left == 0 && named_a_left != 0) {
    a_left = named_a_left;
    out.facing = FacingCue::kNames;
  }
  // Nothing tells: +Z is the facing (glTF's convention, and most BVH captures').
  if (a_left == 0 && b.legs_cut()) a_left = forward_if_a_left(t.p, b.leg_a, b.leg_b).z() >= 0 ? 1 : -1;
  return a_left;
}

// RigStructure::summary: what was found, from what left was told, what is missing.
std::string summarize(const Skeleton& skeleton, const Body& b, bool sides_told, FacingCue facing) {
  std::string found = "hips " + quoted(skeleton, b.hips);
  std::vector<std::string> missing;
  if (b.legs_cut()) {
    found += " with two legs";
    if (b.leg_a.ik || b.leg_b.ik) found += " (an ankle from the joint at the shin's end)";
  } else {
    missing.push_back("legs cut into thigh and shin (no two long bones)");
  }
  if (!b.sides_apart) missing.push_back("left and right (the legs stand at one place in the rest pose)");
  if (b.head >= 0) found += ", spine to the head " + quoted(skeleton, b.head);
  else missing.push_back(b.spine.empty() ? "spine (no chain goes up from the hips)" : "head");
  if (b.chest_at >= 0) found += ", arms from " + quoted(skeleton, b.spine[b.chest_at]);
  else if (!b.spine.empty()) missing.push_back("arms (no two chains leave the spine sideways)");
  if (sides_told) found += std::string("; left told by ") + facing_cue_name(facing);
  if (missing.empty()) return found;
  found += "; not found: ";
  for (size_t i = 0; i < missing.size(); ++i) found += (i ? ", " : "") + missing[i];
  return found;
}

}  // namespace

RigStructure find_rig_structure(const Skeleton& skeleton, const MotionMatrix* motion, const MajorMapping* named) {
  RigStructure out;
  if (motion != nullptr && (motion->cols() != skeleton.channel_count || motion->rows() == 0)) motion = nullptr;
  // A rest pose that shows no standing body (a BVH written with every rotation zero from bones
  // that run along their own axes, or lying as a Z-up file's skeleton does) is read in a pose of
  // the motion instead: the first frame's, when it shows the legs most frames show.
  std::vector<Eigen::Vector3d> pose = rest_positions(skeleton);
  bool from_motion = false;
  std::string which_pose = "the first frame's pose";
  // The legs a pose shows: (hips, one leg's root, the other's), the roots in order; none: -1s.
  const auto legs_of = [&](const std::vector<Eigen::Vector3d>& p) {
    const Tree probe(skeleton, p);
    int hips = -1, a = -1, b = -1;
    if (!(probe.height > 0) || !find_legs(probe, &hips, &a, &b)) return std::array<int, 3>{-1, -1, -1};
    return std::array<int, 3>{hips, std::min(a, b), std::max(a, b)};
  };
  if (legs_of(pose)[0] < 0 && motion != nullptr) {
    // Poses over the motion, the first frame first. A pose with a foot in the air can show other
    // limbs as its legs (the arms hang lower than a lifted foot): the legs most poses show win,
    // read in the first pose that shows them.
    std::vector<std::vector<Eigen::Vector3d>> poses = sample_positions(skeleton, *motion);
    std::vector<std::array<int, 3>> found;
    for (const auto& p : poses) found.push_back(legs_of(p));
    size_t best = found.size(), votes = 0;
    for (size_t k = 0; k < found.size(); ++k) {
      if (found[k][0] < 0) continue;
      const size_t n = static_cast<size_t>(std::count(found.begin(), found.end(), found[k]));
      if (n > votes) {
        votes = n;
        best = k;
      }
    }
    if (best < found.size()) {
      pose = std::move(poses[best]);
      from_motion = true;
      if (best > 0) which_pose = "a pose of the motion that stands on both legs";
    }
  }
  Tree t(skeleton, std::move(pose));
  Body b;
  if (!(t.height > 0) || !find_legs(t, &b.hips, &b.root_a, &b.root_b)) {
    out.summary = !(t.height > 0) ? "the rest pose is flat: no joint stands above another"
                                  : "no legs: no joint has two chains of a like length going down to the lowest joints";
    return out;
  }
  if (motion != nullptr) find_markers(t, *motion);
  b.leg_a = cut_limb(t, b.root_a, false);
  b.leg_b = cut_limb(t, b.root_b, false);
  b.spine_base = b.hips;
  b.spine = find_spine(t, b.hips, b.root_a, b.root_b, &b.spine_base);
  find_sides(t, b);
  find_arms(t, b);
  find_head_and_spine(t, b);
  find_ik_ankles(t, b);
  const int a_left = tell_left(skeleton, t, !from_motion, motion, named, b, out);

  out.joint[static_cast<int>(MajorJoint::kHips)] = b.hips;
  out.joint[static_cast<int>(MajorJoint::kSpine)] = b.lower_spine;
  if (b.chest_at >= 0) out.joint[static_cast<int>(MajorJoint::kChest)] = b.spine[b.chest_at];
  out.joint[static_cast<int>(MajorJoint::kHead)] = b.head;
  const auto put = [&](const Limb& limb, MajorJoint upper) {
    const int u = static_cast<int>(upper);
    out.joint[u] = limb.upper;
    out.joint[u + 1] = limb.middle;
    out.joint[u + 2] = limb.end;
    out.joint[u + 3] = limb.tip;
  };
  if (a_left != 0) {
    put(a_left > 0 ? b.leg_a : b.leg_b, MajorJoint::kLeftHip);
    put(a_left > 0 ? b.leg_b : b.leg_a, MajorJoint::kRightHip);
    put(a_left > 0 ? b.arm_a : b.arm_b, MajorJoint::kLeftShoulder);
    put(a_left > 0 ? b.arm_b : b.arm_a, MajorJoint::kRightShoulder);
  }
  out.summary = summarize(skeleton, b, a_left != 0, out.facing);
  if (from_motion) out.summary = "read in " + which_pose + " (the rest pose shows no legs): " + out.summary;
  return out;
}

}  // namespace mostyle
