#include "engine/export/export_solve.h"

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <string>

#include "engine/io/motion_file.h"
#include "engine/io/bvh/bvh_read.h"
#include "engine/kinematics/convert.h"
#include "engine/base/error.h"
#include "engine/kinematics/euler.h"
#include "engine/kinematics/kinematics.h"
#include "engine/kinematics/resample.h"

namespace mostyle {
namespace {

// Directions shorter than this fraction of the skeleton's size have none (a target on top of
// its parent): the joint then keeps A's rotation for that child.
constexpr double kNoDirection = 1e-9;
// Kabsch with all child directions on one line leaves the twist about it undefined.
constexpr double kCollinear = 1e-9;
// Damping of the refinement of a joint with several children, as file units of error per radian
// relative to the skeleton's size: only keeps the normal equations regular.
constexpr double kDamping = 1e-6;
// Children placed within this fraction of the skeleton's size count as placed exactly.
constexpr double kExactCost = 1e-10;
// A frame whose fit is this many times worse than the previous frame's looks caught in another
// minimum: more starts are tried.
constexpr double kWorseFit = 4.0;
// A joint with several children whose fit has more than one minimum (targets its children cannot
// all reach: a chest whose neck and clavicles pivot leaves a valley of near-equal fits) keeps to
// the one near its rotation on the frame before: a minimum elsewhere is taken only when it fits
// better by more than this (a fraction of the skeleton's size per radian of the turn, squared).
// Else the chest turns back and forth between them from one frame to the next, and the neck and
// collars with it (a pop).
constexpr double kCoherence = 0.05;
// Two fits this many radians apart or more are two minima (the coherence above chooses between
// them); nearer, one minimum reached from two starts, the lower cost is taken.
constexpr double kDistinctMinima = 0.05;

// One child column of a joint with several: reached through a pivot (the first joint below with
// its own rotation, such as a clavicle or a neck base) or, without one, rigidly.
struct ChildLink {
  int column = -1;
  int pivot = -1;                 // joint, or -1
  std::vector<int> to_pivot;      // joints below the parent down to the pivot (with one)
  std::vector<int> to_child;      // joints below the pivot (or the parent) down to the column
};

// What the solve needs to know about one joint, fixed for all frames.
struct JointPlan {
  int column = -1;                 // target column, -1 for a joint without a target
  bool rotates = false;            // has exactly three rotation channels
  EulerOrder order = EulerOrder::kXYZ;
  int rotation_channels[3] = {0, 0, 0};  // frame-row indices, in channel order
  int aim_column = -1;             // the column this joint points at (one child, or as a pivot)
  std::vector<int> aim_chain;      // joints below this one down to aim_column
  std::vector<ChildLink> children; // two or more child columns: a best-fit rotation
};

// Position of joint `chain.back()` in the frame of the joint above `chain.front()` (after its
// own rotation), at A's local rotations and translations: the bone from a joint to a child
// column through any joints in between.
Eigen::Vector3d chain_vector(const std::vector<int>& chain, const std::vector<Eigen::Matrix3d>& local_rotation,
                             const std::vector<Eigen::Vector3d>& local_translation) {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  for (size_t i = 0; i < chain.size(); ++i) {
    position += rotation * local_translation[chain[i]];
    if (i + 1 < chain.size()) rotation = rotation * local_rotation[chain[i]];
  }
  return position;
}

Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

Eigen::Matrix3d rotation_from_vector(const Eigen::Vector3d& w) {
  const double angle = w.norm();
  if (angle == 0.0) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
}

// The rotation that best turns the unit directions `from` into `to` (Kabsch; Wahba's problem):
// with one direction the smallest rotation between them.
Eigen::Matrix3d best_rotation(const std::vector<Eigen::Vector3d>& from, const std::vector<Eigen::Vector3d>& to) {
  if (from.empty()) return Eigen::Matrix3d::Identity();
  if (from.size() >= 2) {
    Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
    for (size_t i = 0; i < from.size(); ++i) h += from[i] * to[i].transpose();
    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(h, Eigen::ComputeFullU | Eigen::ComputeFullV);
    const Eigen::Vector3d s = svd.singularValues();
    if (s[1] > kCollinear * s[0]) {
      Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
      d(2, 2) = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0 ? -1.0 : 1.0;
      return svd.matrixV() * d * svd.matrixU().transpose();
    }
  }
  return Eigen::Quaterniond::FromTwoVectors(from[0], to[0]).toRotationMatrix();
}

// Per child of a joint with several, in that joint's frame: with a pivot, where the pivot is
// and how far the child is from it (the pivot turns freely, so only that distance is fixed);
// without, where the child is.
struct ChildGeometry {
  Eigen::Vector3d target;
  Eigen::Vector3d offset;  // pivot or child position in the joint's frame
  double reach = 0.0;      // pivot to child distance; < 0: no pivot
};

double fit_cost(const std::vector<ChildGeometry>& children, const Eigen::Vector3d& position,
                const Eigen::Matrix3d& rotation) {
  double cost = 0.0;
  for (const ChildGeometry& c : children) {
    const Eigen::Vector3d q = c.target - position - rotation * c.offset;
    cost += c.reach < 0 ? q.squaredNorm() : (q.norm() - c.reach) * (q.norm() - c.reach);
  }
  return cost;
}

// Refines `rotation` (a joint's global one, started from the Kabsch fit of the directions) so
// that the children land on their targets: a rigid child's position error, a pivoted child's
// distance error (the pivot then turns the rest of the way), both in file units, least squares
// by damped Gauss-Newton on a rotation vector with backtracking. Directions the children do not
// constrain (pivots at the joint itself) get no step, so they stay at the direction fit.
// `damping`: file units squared per radian squared.
Eigen::Matrix3d refine_rotation(const std::vector<ChildGeometry>& children, const Eigen::Vector3d& position,
                                Eigen::Matrix3d rotation, double damping) {
  constexpr int kIterations = 30;
  constexpr int kHalvings = 12;
  double cost = fit_cost(children, position, rotation);
  for (int it = 0; it < kIterations && cost > 0; ++it) {
    Eigen::Matrix3d jtj = damping * Eigen::Matrix3d::Identity();
    Eigen::Vector3d jte = Eigen::Vector3d::Zero();
    for (const ChildGeometry& c : children) {
      const Eigen::Vector3d rotated = rotation * c.offset;
      const Eigen::Vector3d q = c.target - position - rotated;
      // d(exp(w) R o)/dw = -[R o]x, so q moves by +[R o]x w.
      const Eigen::Matrix3d dq = cross_matrix(rotated);
      if (c.reach < 0) {
        jtj += dq.transpose() * dq;
        jte += dq.transpose() * q;
      } else if (q.norm() > 0) {
        const Eigen::RowVector3d row = q.normalized().transpose() * dq;
        jtj += row.transpose() * row;
        jte += row.transpose() * (q.norm() - c.reach);
      }
    }
    Eigen::Vector3d step = -jtj.ldlt().solve(jte);
    if (!step.allFinite()) break;
    // Backtracking: far from the optimum the linear model of a rotation can overshoot.
    Eigen::Matrix3d next;
    double next_cost = cost;
    for (int halving = 0; halving < kHalvings; ++halving, step *= 0.5) {
      next = rotation_from_vector(step) * rotation;
      next_cost = fit_cost(children, position, next);
      if (next_cost < cost) break;
    }
    if (!(next_cost < cost)) break;
    rotation = next;
    const double gain = cost - next_cost;
    cost = next_cost;
    if (step.norm() < 1e-14 || gain <= 1e-16 * (1.0 + cost)) break;
  }
  return rotation;
}

// Angle between two rotations, radians.
double rotation_distance(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return Eigen::AngleAxisd(a.transpose() * b).angle();
}

// What a fit of several children weighs, in file units squared (from the skeleton's size): the
// damping of refine_rotation (per radian squared), the coherence with the frame before (per
// radian squared of turn) and the cost under which every child is placed.
struct FitCosts {
  double damping = 0.0, coherence = 0.0, exact_cost = 0.0;
};

// The rotation of a joint with several children: refine_rotation from the direction fit; where
// that stops short of placing every child (the least squares has other minima), also from the
// previous frame's solution and from the direction fit turned a quarter turn about each axis,
// keeping a fit that places every child (within exact_cost) over one that does not, among such
// fits the rotation nearest the direction fit (the one that changes A's pose least), and among
// the others the lowest cost, counted, between two distinct minima, with coherence times the
// squared turn from the frame before's rotation. previous: null on the first frame.
Eigen::Matrix3d solve_several(const std::vector<ChildGeometry>& children, const Eigen::Vector3d& position,
                              const Eigen::Matrix3d& start, const Eigen::Matrix3d* previous,
                              double previous_cost, const FitCosts& costs, double* cost_out) {
  const double damping = costs.damping, coherence = costs.coherence, exact_cost = costs.exact_cost;
  auto score = [&](const Eigen::Matrix3d& r, double cost) {
    if (!previous) return cost;
    const double turn = rotation_distance(r, *previous);
    return cost + coherence * turn * turn;
  };
  Eigen::Matrix3d best = refine_rotation(children, position, start, damping);
  double best_cost = fit_cost(children, position, best);
  auto consider = [&](const Eigen::Matrix3d& from) {
    const Eigen::Matrix3d r = refine_rotation(children, position, from, damping);
    const double cost = fit_cost(children, position, r);
    const bool exact = cost <= exact_cost, best_exact = best_cost <= exact_cost;
    const bool better = exact && best_exact ? rotation_distance(r, start) < rotation_distance(best, start)
                        : exact != best_exact                               ? exact
                        : rotation_distance(r, best) > kDistinctMinima ? score(r, cost) < score(best, best_cost)
                                                                        : cost < best_cost;
    if (better) {
      best = r;
      best_cost = cost;
    }
  };
  if (best_cost > exact_cost && previous) consider(*previous);
  // Quarter turns only when this frame fits clearly worse than the last did (a new minimum
  // appeared elsewhere), or on the first frame: where the targets are simply out of reach every
  // frame, every start ends at the same cost.
  if (best_cost > exact_cost && (!previous || best_cost > kWorseFit * previous_cost + exact_cost)) {
    for (int axis = 0; axis < 3; ++axis)
      for (double angle : {-90.0, 90.0}) consider(axis_rotation(axis, angle) * start);
  }
  *cost_out = best_cost;
  return best;
}

double skeleton_size(const Skeleton& skeleton) {
  const std::vector<Eigen::Vector3d> rest = rest_positions(skeleton);
  double size = 0;
  for (const auto& p : rest) size = std::max(size, (p - rest.front()).norm());
  return size > 0 ? size : 1.0;
}

void check_targets(const Clip& clip, const std::vector<int>& joints, const Eigen::MatrixXd& world,
                   const char* where) {
  const int n = static_cast<int>(clip.skeleton.joints.size());
  if (world.cols() != 3 * static_cast<Eigen::Index>(joints.size()))
    throw InputError(std::string(where) + ": positions have " + std::to_string(world.cols()) +
                     " columns, expected 3 per joint for " + std::to_string(joints.size()) + " joints");
  std::vector<char> seen(static_cast<size_t>(n), 0);
  for (int j : joints) {
    if (j < 0 || j >= n || clip.skeleton.joints[j].end_site)
      throw InputError(std::string(where) + ": " + clip.source + " has no joint " + std::to_string(j) +
                       " to place (End Sites cannot be targets)");
    if (seen[j]) throw InputError(std::string(where) + ": joint '" + clip.skeleton.joints[j].name + "' is listed twice");
    seen[j] = 1;
  }
  if (!world.allFinite()) throw InputError(std::string(where) + ": the target positions are not all finite numbers");
}

ExportResult solve_on(Clip sampled, const Clip& clip, const std::vector<int>& joints, const Eigen::MatrixXd& world);

}  // namespace

ExportResult solve_export(const Clip& clip, const std::vector<int>& joints, const Eigen::MatrixXd& world,
                          double fps) {
  check_targets(clip, joints, world, "export");
  // The same rule as extract_major_take, so frames line up with the blend's.
  const bool same_rate = fps <= 0 || std::abs(fps - clip.fps()) < 1e-9;
  return solve_on(same_rate ? clip : resample_clip(clip, fps), clip, joints, world);
}

ExportResult solve_export_at(const Clip& clip, const std::vector<int>& joints, const Eigen::MatrixXd& world,
                             const Eigen::VectorXd& at, double fps) {
  check_targets(clip, joints, world, "export");
  if (at.size() != world.rows())
    throw InputError("export: " + std::to_string(world.rows()) + " frames of positions for " +
                     std::to_string(at.size()) + " source times");
  return solve_on(sample_clip(clip, at, fps), clip, joints, world);
}

// What the per-frame solve keeps: the plan for the skeleton (fixed) and the frame before's
// angles and fits (the solve continues from them).
struct ExportFrameSolver::State {
  Skeleton skeleton;
  std::vector<JointPlan> plan;
  std::vector<std::vector<int>> chain;  // per column: the joints from its column ancestor down to it
  int top = -1;                         // the topmost column
  int carrier = -1;                     // the joint that carries the trajectory
  std::vector<int> carrier_chain;       // joints below the carrier down to the top column's joint
  double min_length = 0.0;
  FitCosts costs;
  bool first = true;
  std::vector<Eigen::Matrix3d> local_rotation;
  std::vector<Eigen::Vector3d> local_translation, previous;
  Pose world;  // per joint, as solved so far in this frame
  std::vector<Eigen::Vector3d> from, to;
  std::vector<ChildGeometry> geometry;
  std::vector<double> previous_cost;  // joints with several children

  // The vector from the first of `joints_below` down the chain, at the local values now set.
  Eigen::Vector3d vector_of(const std::vector<int>& joints_below) const {
    return chain_vector(joints_below, local_rotation, local_translation);
  }
  // Column c's target.
  static Eigen::Vector3d target(const double* targets, int c) {
    return Eigen::Vector3d(targets[3 * c], targets[3 * c + 1], targets[3 * c + 2]);
  }
  Eigen::Vector3d place_carrier(int j, const Eigen::Matrix3d& parent_rotation, const Eigen::Vector3d& parent_position,
                                const double* targets, double* row) const;
  bool turn_to_children(int j, const Eigen::Matrix3d& parent_rotation, const double* targets);
  bool aim_at_child(int j, const double* targets);
};

namespace {

// Throws InputError on a joint to place that the skeleton lacks, an End Site, or one listed twice.
void check_export_joints(const Skeleton& skeleton, const std::vector<int>& joints, const std::string& source) {
  const int n = static_cast<int>(skeleton.joints.size());
  std::vector<char> seen(static_cast<size_t>(n), 0);
  for (int j : joints) {
    if (j < 0 || j >= n || skeleton.joints[j].end_site)
      throw InputError("export: " + source + " has no joint " + std::to_string(j) +
                       " to place (End Sites cannot be targets)");
    if (seen[j]) throw InputError("export: joint '" + skeleton.joints[j].name + "' is listed twice");
    seen[j] = 1;
  }
}

// Each joint's column and rotation channels (aims left for plan_aims).
std::vector<JointPlan> rotation_plan(const Skeleton& skeleton, const std::vector<int>& joints) {
  const int n = static_cast<int>(skeleton.joints.size());
  std::vector<JointPlan> plan(static_cast<size_t>(n));
  for (int c = 0; c < static_cast<int>(joints.size()); ++c) plan[joints[c]].column = c;
  for (int j = 0; j < n; ++j) {
    const Joint& joint = skeleton.joints[j];
    JointPlan& p = plan[j];
    p.rotates = !joint.end_site && joint_euler_order(joint, &p.order);
    if (!p.rotates) continue;
    int k = 0;
    for (size_t c = 0; c < joint.channels.size(); ++c)
      if (is_rotation(joint.channels[c])) p.rotation_channels[k++] = joint.first_channel + static_cast<int>(c);
  }
  return plan;
}

// How the columns hang together: each column's nearest column ancestor and the joints from there
// down to it, each joint's child columns, and how many of those ways pass through each joint.
struct ColumnTree {
  std::vector<std::vector<int>> chain;         // per column
  std::vector<int> parent_column;              // per column, -1 for none
  std::vector<std::vector<int>> child_columns; // per joint
  std::vector<int> chains_through;             // per joint
};

ColumnTree column_tree(const Skeleton& skeleton, const std::vector<int>& joints, const std::vector<JointPlan>& plan) {
  const int n = static_cast<int>(skeleton.joints.size());
  const int m = static_cast<int>(joints.size());
  ColumnTree tree;
  tree.chain.resize(static_cast<size_t>(m));
  tree.parent_column.assign(static_cast<size_t>(m), -1);
  tree.child_columns.resize(static_cast<size_t>(n));
  tree.chains_through.assign(static_cast<size_t>(n), 0);
  for (int c = 0; c < m; ++c) {
    std::vector<int> path{joints[c]};
    for (int a = skeleton.joints[joints[c]].parent; a >= 0; a = skeleton.joints[a].parent) {
      if (plan[a].column >= 0) {
        tree.parent_column[c] = plan[a].column;
        tree.child_columns[a].push_back(c);
        break;
      }
      path.push_back(a);
    }
    tree.chain[c].assign(path.rbegin(), path.rend());
    for (size_t i = 0; i + 1 < tree.chain[c].size(); ++i) ++tree.chains_through[tree.chain[c][i]];
  }
  return tree;
}

// What each joint aims at: its one child column, or with several, a link to each (through a
// pivot where one below it turns on its own).
void plan_aims(const ColumnTree& tree, std::vector<JointPlan>& plan) {
  const std::vector<std::vector<int>>& chain = tree.chain;
  for (size_t j = 0; j < plan.size(); ++j) {
    const std::vector<int>& kids = tree.child_columns[j];
    if (kids.size() == 1) {
      plan[j].aim_column = kids[0];
      plan[j].aim_chain = chain[kids[0]];
      continue;
    }
    for (int c : kids) {
      // A joint with several children cannot aim them all; the first joint below it on the way
      // to one child that turns on its own (a clavicle, a neck base, CMU's LHipJoint) takes up
      // the rest of that child's direction. Joints shared by two ways are left as they are.
      ChildLink link;
      link.column = c;
      link.to_child = chain[c];
      for (size_t i = 0; i + 1 < chain[c].size(); ++i) {
        const int k = chain[c][i];
        if (!plan[k].rotates || tree.chains_through[k] != 1) continue;
        link.pivot = k;
        link.to_pivot.assign(chain[c].begin(), chain[c].begin() + i + 1);
        link.to_child.assign(chain[c].begin() + i + 1, chain[c].end());
        plan[k].aim_column = c;
        plan[k].aim_chain = link.to_child;
        break;
      }
      plan[j].children.push_back(link);
    }
  }
}

// The joint that carries the trajectory: the nearest at or above `from` (the topmost column's
// joint, or -1) with position channels (Bandai: Hips itself, not the still ROOT above it), or -1;
// below_carrier: the joints below it down to `from`, top down.
int trajectory_carrier(const Skeleton& skeleton, int from, std::vector<int>& below_carrier) {
  int carrier = -1;
  for (int a = from; a >= 0; a = skeleton.joints[a].parent) {
    const auto& channels = skeleton.joints[a].channels;
    if (std::any_of(channels.begin(), channels.end(), is_position)) {
      carrier = a;
      break;
    }
    below_carrier.push_back(a);
  }
  std::reverse(below_carrier.begin(), below_carrier.end());
  return carrier;
}

}  // namespace

ExportFrameSolver::ExportFrameSolver(const Skeleton& skeleton_in, const std::vector<int>& joints,
                                     const std::string& source)
    : state_(std::make_unique<State>()) {
  State& s = *state_;
  s.skeleton = skeleton_in;
  const Skeleton& skeleton = s.skeleton;
  const int n = static_cast<int>(skeleton.joints.size());
  const int m = static_cast<int>(joints.size());
  check_export_joints(skeleton, joints, source);
  s.plan = rotation_plan(skeleton, joints);
  ColumnTree tree = column_tree(skeleton, joints, s.plan);
  plan_aims(tree, s.plan);
  s.chain = std::move(tree.chain);
  // The topmost column (the hips).
  for (int c = 0; c < m; ++c)
    if (tree.parent_column[c] < 0 && (s.top < 0 || joints[c] < joints[s.top])) s.top = c;
  s.carrier = trajectory_carrier(skeleton, s.top >= 0 ? joints[s.top] : -1, s.carrier_chain);
  const double size = skeleton_size(skeleton);
  s.min_length = kNoDirection * size;
  s.costs.damping = (kDamping * size) * (kDamping * size);
  s.costs.coherence = (kCoherence * size) * (kCoherence * size);
  s.costs.exact_cost = (kExactCost * size) * (kExactCost * size);

  s.local_rotation.resize(static_cast<size_t>(n));
  s.world.rotations.resize(static_cast<size_t>(n));
  s.local_translation.resize(static_cast<size_t>(n));
  s.world.positions.resize(static_cast<size_t>(n));
  s.previous.assign(static_cast<size_t>(n), Eigen::Vector3d::Zero());
  s.previous_cost.assign(static_cast<size_t>(n), 0.0);
  // At most one entry per child column of a joint: reserved so that no frame allocates.
  s.from.reserve(static_cast<size_t>(m));
  s.to.reserve(static_cast<size_t>(m));
  s.geometry.reserve(static_cast<size_t>(m));
}

ExportFrameSolver::~ExportFrameSolver() = default;
ExportFrameSolver::ExportFrameSolver(ExportFrameSolver&&) noexcept = default;
ExportFrameSolver& ExportFrameSolver::operator=(ExportFrameSolver&&) noexcept = default;

void ExportFrameSolver::restart() { state_->first = true; }

// The carrier's local translation that lands the top column on its target (position channels
// replace the OFFSET, as Blender reads them; a missing position channel stays 0, as readers take
// it), written into `row`.
Eigen::Vector3d ExportFrameSolver::State::place_carrier(int j, const Eigen::Matrix3d& parent_rotation,
                                                        const Eigen::Vector3d& parent_position, const double* targets,
                                                        double* row) const {
  const Joint& joint = skeleton.joints[j];
  const Eigen::Matrix3d rotation = parent_rotation * local_rotation[j];
  const Eigen::Vector3d below =
      carrier_chain.empty() ? Eigen::Vector3d::Zero() : Eigen::Vector3d(rotation * vector_of(carrier_chain));
  const Eigen::Vector3d wanted = parent_rotation.transpose() * (target(targets, top) - below - parent_position);
  for (size_t c = 0; c < joint.channels.size(); ++c)
    if (is_position(joint.channels[c])) row[joint.first_channel + c] = wanted[channel_axis(joint.channels[c])];
  return joint_local_translation(joint, row);
}

// Several children (hips, chest): joint j's world rotation turned by the best-fit rotation of the
// directions to them (Kabsch), refined so the children themselves land (pivots take up the rest).
// False, the rotation untouched, when no direction is long enough to tell.
bool ExportFrameSolver::State::turn_to_children(int j, const Eigen::Matrix3d& parent_rotation, const double* targets) {
  const JointPlan& p = plan[j];
  from.clear();
  to.clear();
  geometry.clear();
  for (const ChildLink& link : p.children) {
    const Eigen::Vector3d u = world.rotations[j] * vector_of(link.pivot >= 0 ? chain[link.column] : link.to_child);
    const Eigen::Vector3d v = target(targets, link.column) - world.positions[j];
    if (u.norm() > min_length && v.norm() > min_length) {
      from.push_back(u.normalized());
      to.push_back(v.normalized());
    }
    ChildGeometry g;
    g.target = target(targets, link.column);
    if (link.pivot >= 0) {
      g.offset = vector_of(link.to_pivot);
      g.reach = vector_of(link.to_child).norm();
    } else {
      g.offset = vector_of(link.to_child);
    }
    geometry.push_back(g);
  }
  if (from.empty()) return false;
  const Eigen::Matrix3d start = best_rotation(from, to) * world.rotations[j];
  const Eigen::Matrix3d last = parent_rotation * euler_to_matrix(p.order, previous[j]);
  world.rotations[j] = solve_several(geometry, world.positions[j], start, !first ? &last : nullptr, previous_cost[j], costs,
                                     &previous_cost[j]);
  return true;
}

// One child (or a pivot): the smallest rotation that turns A's bone, at the parent's solved
// rotation and A's own local one (so twist is kept), toward the child's target, seen from where
// joint j now is, so errors do not accumulate down a chain. False when either is too short.
bool ExportFrameSolver::State::aim_at_child(int j, const double* targets) {
  const JointPlan& p = plan[j];
  const Eigen::Vector3d u = world.rotations[j] * vector_of(p.aim_chain);
  const Eigen::Vector3d v = target(targets, p.aim_column) - world.positions[j];
  if (!(u.norm() > min_length && v.norm() > min_length)) return false;
  world.rotations[j] = Eigen::Quaterniond::FromTwoVectors(u, v).toRotationMatrix() * world.rotations[j];
  return true;
}

void ExportFrameSolver::solve(const double* a_row, const double* targets, double* row) {
  State& s = *state_;
  const Skeleton& skeleton = s.skeleton;
  const int n = static_cast<int>(skeleton.joints.size());
  // Every value the solve does not set is A's.
  if (row != a_row) std::copy(a_row, a_row + skeleton.channel_count, row);
  for (int j = 0; j < n; ++j) {
    s.local_rotation[j] = joint_local_rotation(skeleton.joints[j], a_row);
    s.local_translation[j] = joint_local_translation(skeleton.joints[j], a_row);
  }
  for (int j = 0; j < n; ++j) {
    const Joint& joint = skeleton.joints[j];
    const JointPlan& p = s.plan[j];
    // The parent's frame as solved (a root's: the world's).
    const Eigen::Matrix3d parent_rotation =
        joint.parent >= 0 ? s.world.rotations[joint.parent] : Eigen::Matrix3d::Identity();
    const Eigen::Vector3d parent_position =
        joint.parent >= 0 ? s.world.positions[joint.parent] : Eigen::Vector3d::Zero();
    const Eigen::Vector3d translation =
        j == s.carrier ? s.place_carrier(j, parent_rotation, parent_position, targets, row) : s.local_translation[j];
    place_joint(skeleton, j, s.local_rotation[j], translation, &s.world);
    if (!p.rotates) continue;
    Eigen::Vector3d angles;
    for (int d = 0; d < 3; ++d) angles[d] = a_row[p.rotation_channels[d]];
    const Eigen::Vector3d near = !s.first ? s.previous[j] : angles;
    const bool solved = p.children.size() >= 2 ? s.turn_to_children(j, parent_rotation, targets)
                        : p.aim_column >= 0    ? s.aim_at_child(j, targets)
                                               : false;
    if (solved) {
      angles = matrix_to_euler_near(p.order, parent_rotation.transpose() * s.world.rotations[j], near);
    } else if (!s.first) {
      angles = euler_near(angles, near);
    }
    for (int d = 0; d < 3; ++d) row[p.rotation_channels[d]] = angles[d];
    s.previous[j] = angles;
  }
  s.first = false;
}

namespace {

ExportResult solve_on(Clip sampled, const Clip& clip, const std::vector<int>& joints, const Eigen::MatrixXd& world) {
  ExportResult result;
  result.clip = std::move(sampled);
  Clip& out = result.clip;
  const Clip source = out;  // A's values at the output rate; `out` is overwritten frame by frame
  if (world.rows() != out.frames())
    throw InputError("export: " + std::to_string(world.rows()) + " frames of positions for " +
                     std::to_string(out.frames()) + " frames of " + clip.source + " at the output rate");
  ExportFrameSolver solver(out.skeleton, joints, clip.source);
  Eigen::VectorXd targets(world.cols());
  for (int f = 0; f < out.frames(); ++f) {
    targets = world.row(f).transpose();
    solver.solve(source.motion.row(f).data(), targets.data(), out.motion.row(f).data());
  }
  result.fit = export_fit(out, joints, world);
  return result;
}

}  // namespace

ExportResult solve_export_in_layout(const Clip& clip, const std::vector<int>& joints, const Eigen::MatrixXd& world,
                                    const Eigen::VectorXd& at, double fps, ChannelLayout layout) {
  ExportResult result = solve_export_at(clip, joints, world, at, fps);
  // The layout is applied to the solved clip, not to A: the solve moves the joint that carries
  // the trajectory (Bandai's Hips, the trajectory child there), which A's values would not show.
  if (layout == ChannelLayout::kRotations) result.clip = with_rotation_channels(result.clip);
  return result;
}

ExportResult export_blend_bvh(const Clip& clip, const std::vector<int>& joints, const Eigen::MatrixXd& world,
                              const Eigen::VectorXd& at, double fps, const std::string& path,
                              ChannelLayout layout) {
  ExportResult result = solve_export_in_layout(clip, joints, world, at, fps, layout);
  write_motion_file(result.clip, path);
  return result;
}

ExportFit export_fit(const Clip& clip, const std::vector<int>& joints, const Eigen::MatrixXd& world) {
  check_targets(clip, joints, world, "export fit");
  if (world.rows() != clip.frames())
    throw InputError("export fit: " + std::to_string(world.rows()) + " frames of positions for " +
                     std::to_string(clip.frames()) + " frames of " + clip.source);
  const Eigen::MatrixXd all = joint_positions(clip);
  ExportFit fit;
  double sum = 0;
  for (Eigen::Index f = 0; f < world.rows(); ++f) {
    for (size_t c = 0; c < joints.size(); ++c) {
      const double d = (all.block<1, 3>(f, 3 * joints[c]) - world.block<1, 3>(f, 3 * c)).norm();
      fit.max = std::max(fit.max, d);
      sum += d;
    }
  }
  const double count = static_cast<double>(world.rows()) * static_cast<double>(joints.size());
  fit.mean = count > 0 ? sum / count : 0.0;
  return fit;
}

}  // namespace mostyle
