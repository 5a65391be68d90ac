
#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "engine/align/time_warp.h"
#include "engine/base/atomic_file.h"
#include "engine/io/bvh/bvh_read.h"
#include "engine/kinematics/convert.h"
#include "engine/base/error.h"
#include "engine/kinematics/euler.h"
#include "engine/kinematics/kinematics.h"
#include "engine/kinematics/limb_length.h"
#include "engine/prepare/major_take.h"
#include "engine/kinematics/resample.h"
#include "engine/kinematics/units.h"
#include "tests/engine/skeleton_builder.h"
#include "tests/engine/worker/blend_at.h"
#include "tests/test_data.h"

using namespace mostyle;
using mostyle::test::blend_at;

namespace {

// Acceptance bounds, as fractions of the skeleton's height (guess_units).
constexpr double kSelfBlendMean = 0.02;   // a take blended with itself, mean joint distance
constexpr double kAlphaZeroMean = 0.03;   // alpha = 0 against A
constexpr double kGrossError = 0.25;      // no joint of any frame this far off (flips, jumps)
constexpr double kBonesExact = 1e-9;      // bone length error relative to the longest bone
constexpr double kSameTake = 1e-9;        // results that must agree to rounding, file units
const double kAlphas[] = {0.0, 0.25, 0.5, 0.75, 1.0};

// The paper's reproduction settings: k = 20 components, sparsity 1.
DecomposeParams reproduction_params() {
  DecomposeParams d;
  d.components = 20;
  d.sparsity = 1.0;
  return d;
}

std::shared_ptr<const Clip> load(const std::string& path) {
  return std::make_shared<const Clip>(read_bvh_file(path));
}

std::string base_name(const std::string& path) { return path.substr(path.find_last_of('/') + 1); }

// Mean and largest joint distance between two F x 3M position matrices, as fractions of height.
struct Distance {
  double mean = 0, max = 0;
};
Distance distance(const Eigen::MatrixXd& x, const Eigen::MatrixXd& reference, double height) {
  REQUIRE(x.rows() == reference.rows());
  REQUIRE(x.cols() == reference.cols());
  Distance d;
  const Eigen::Index joints = x.cols() / 3;
  for (Eigen::Index t = 0; t < x.rows(); ++t) {
    for (Eigen::Index j = 0; j < joints; ++j) {
      const double e = (x.block<1, 3>(t, 3 * j) - reference.block<1, 3>(t, 3 * j)).norm();
      d.mean += e;
      d.max = std::max(d.max, e);
    }
  }
  d.mean /= static_cast<double>(x.rows() * joints) * height;
  d.max /= height;
  return d;
}

// A's own FK, resampled to the working rate, at its mapped major joints: what a blend at
// alpha = 0 must reproduce. Computed here from resample_clip and joint_positions directly.
Eigen::MatrixXd reference_positions(const Clip& a, const PreparedTakes& p) {
  const Clip resampled = std::abs(a.fps() - p.fps) < 1e-9 ? a : resample_clip(a, p.fps);
  const Eigen::MatrixXd all = joint_positions(resampled);
  Eigen::MatrixXd out(all.rows(), 3 * static_cast<Eigen::Index>(p.majors.size()));
  for (size_t i = 0; i < p.majors.size(); ++i)
    out.middleCols(3 * i, 3) = all.middleCols(3 * p.takes[0].mapping.joint[p.majors[i]], 3);
  return out;
}

// The reference at the frames of A a blend shows (MixResult::source_a): a blend plays only A's
// matched range, on its own timeline (trajectory/mixed_clock.h).
// A's file frames at the output's frames, through the replays of its cycles its own timeline
// holds where B has more (frames_in_take).
Eigen::MatrixXd reference_at(const Clip& a, const PreparedTakes& p, const MixResult& r) {
  return sample_rows(reference_positions(a, p), frames_in_take(p.reference(), r.sources.col(0)));
}

double relative_bone_error(const PreparedTakes& p, const Eigen::MatrixXd& world) {
  double longest = 0;
  for (double l : p.lengths) longest = std::max(longest, l);
  return max_bone_length_error(world, p.parents, p.lengths) / longest;
}

// Root-relative, heading-aligned pose of a result (its own canonical frame).
Eigen::MatrixXd canonical_pose(const PreparedTakes& p, const Eigen::MatrixXd& world) {
  const int left = major_column(p.majors, static_cast<int>(MajorJoint::kLeftHip));
  const int right = major_column(p.majors, static_cast<int>(MajorJoint::kRightHip));
  return to_canonical(world, 0, left, right).local;
}

// A clip turned 180 degrees about +Y through the origin: root position (x, z) -> (-x, -z), root
// rotation R -> R_y(180) R. Every joint's world position turns the same way.
Clip turned_around(const Clip& clip) {
  Clip out = clip;
  const Joint& root = clip.skeleton.joints[0];
  EulerOrder order;
  REQUIRE(joint_euler_order(root, &order));
  int rotation[3], k = 0;
  for (size_t c = 0; c < root.channels.size(); ++c) {
    const int column = root.first_channel + static_cast<int>(c);
    if (is_rotation(root.channels[c])) rotation[k++] = column;
    if (root.channels[c] == Channel::kXposition || root.channels[c] == Channel::kZposition)
      out.motion.col(column) = -clip.motion.col(column);
  }
  const Eigen::Matrix3d turn = axis_rotation(1, 180.0);
  Eigen::Vector3d previous = Eigen::Vector3d::Zero();
  for (int f = 0; f < clip.frames(); ++f) {
    const Eigen::Vector3d angles(clip.motion(f, rotation[0]), clip.motion(f, rotation[1]), clip.motion(f, rotation[2]));
    const Eigen::Vector3d turned = matrix_to_euler_near(order, turn * euler_to_matrix(order, angles), previous);
    for (int i = 0; i < 3; ++i) out.motion(f, rotation[i]) = turned[i];
    previous = turned;
  }
  out.source = clip.source + " (turned around)";
  return out;
}

// The same clip in other length units: every OFFSET and position channel times `factor`.
Clip in_other_units(const Clip& clip, double factor) {
  Clip out = clip;
  for (Joint& j : out.skeleton.joints) {
    j.offset *= factor;
    for (size_t c = 0; c < j.channels.size(); ++c)
      if (is_position(j.channels[c])) out.motion.col(j.first_channel + static_cast<int>(c)) *= factor;
  }
  out.source = clip.source + " (x" + std::to_string(factor) + ")";
  return out;
}

struct PairCheck {
  Distance alpha0;                  // against A's FK
  std::vector<double> world_to_b;   // mean distance to the alpha = 1 result, per kAlphas
  std::vector<double> pose_to_b;    // the same in each result's own canonical frame
  double bones = 0;                 // worst relative bone error over all alphas
  bool paper_finite = false;
};

// Blends a pair at every alpha of kAlphas (and, with `paper`, paper mode at 0.5 and 1) and
// measures it. The blends keep A's timeline (timing_a) so that every alpha shows the same
// frames and the distances between them measure the poses, not the timing.
PairCheck check_pair(const std::shared_ptr<const Clip>& a, const std::shared_ptr<const Clip>& b,
                     const PrepareOptions& options = {}, bool paper = true) {
  const auto p = prepare_takes({a, b}, options);
  const auto d = decompose_takes(*p, reproduction_params());
  const double height = guess_units(*a).height;
  PairCheck c;
  std::vector<MixResult> results;
  MixParams on_a;
  on_a.reference_timing = true;
  for (double alpha : kAlphas) results.push_back(blend_at(*p, *d, alpha, on_a));
  c.alpha0 = distance(results.front().motion.world, reference_at(*a, *p, results.front()), height);
  const Eigen::MatrixXd pose_b = canonical_pose(*p, results.back().motion.world);
  for (const MixResult& r : results) {
    c.world_to_b.push_back(distance(r.motion.world, results.back().motion.world, height).mean);
    c.pose_to_b.push_back(distance(canonical_pose(*p, r.motion.world), pose_b, height).mean);
    c.bones = std::max(c.bones, relative_bone_error(*p, r.motion.world));
  }
  if (paper) {
    DecomposeParams params = reproduction_params();
    params.mode = DecompositionMode::kPaper;
    const auto dp = decompose_takes(*p, params);
    c.paper_finite = blend_at(*p, *dp, 0.5).motion.world.allFinite() && blend_at(*p, *dp, 1.0).motion.world.allFinite();
  }
  return c;
}

bool decreasing(const std::vector<double>& v) {
  for (size_t i = 1; i < v.size(); ++i)
    if (!(v[i] < v[i - 1])) return false;
  return true;
}

std::string describe(const std::vector<double>& v) {
  std::string s;
  for (double x : v) s += (s.empty() ? "" : " ") + std::to_string(100 * x) + "%";
  return s;
}

// All checks on one pair: alpha 0 is A; the distance to the alpha = 1 result falls
// as alpha rises, in the world frame and in the pose's own canonical frame; exact bones; paper
// mode finite.
void require_pair(const std::string& path_a, const std::string& path_b) {
  INFO(base_name(path_a) << " + " << base_name(path_b));
  const PairCheck c = check_pair(load(path_a), load(path_b));
  INFO("alpha 0: mean " << 100 * c.alpha0.mean << "%, max " << 100 * c.alpha0.max << "%");
  INFO("world distance to alpha 1: " << describe(c.world_to_b));
  INFO("pose distance to alpha 1: " << describe(c.pose_to_b));
  CHECK(c.alpha0.mean < kAlphaZeroMean);
  CHECK(c.alpha0.max < kGrossError);
  CHECK(decreasing(c.world_to_b));
  CHECK(decreasing(c.pose_to_b));
  CHECK(c.bones < kBonesExact);
  CHECK(c.paper_finite);
}

// Self-blend of one take (shared mode, k = 20, sparsity 1) against its own FK at 30 fps.
void require_self_blend(const std::string& path) {
  INFO(base_name(path));
  const auto clip = load(path);
  const auto p = prepare_takes({clip, clip}, {});
  const auto d = decompose_takes(*p, reproduction_params());
  const double height = guess_units(*clip).height;
  const Eigen::MatrixXd reference = reference_positions(*clip, *p);
  // The pipeline's own FK, in the take's mean bone lengths (a CMU chain of majors skips joints,
  // so its bones vary a little from frame to frame): exactly, and a hair from the file's.
  Eigen::MatrixXd rigid = reference;
  apply_limb_lengths(rigid, p->parents, bone_lengths(reference, p->parents));
  CHECK((p->takes[0].world - rigid).cwiseAbs().maxCoeff() == 0.0);
  CHECK((p->takes[0].world - reference).cwiseAbs().maxCoeff() < 0.005 * height);
  for (double alpha : {0.0, 0.5, 1.0}) {
    const MixResult r = blend_at(*p, *d, alpha);
    CHECK(r.motion.world.rows() == reference.rows());  // a take matches itself from end to end
    const Distance e = distance(r.motion.world, sample_rows(reference, r.sources.col(0)), height);
    INFO("alpha " << alpha << ": mean " << 100 * e.mean << "%, max " << 100 * e.max << "% of height " << height);
    CHECK(e.mean < kSelfBlendMean);
    CHECK(e.max < kGrossError);
    CHECK(relative_bone_error(*p, r.motion.world) < kBonesExact);
  }
}

}  // namespace

TEST_CASE("self-blend reproduces each bundled take", "[pipeline]") {
  const std::vector<std::string> takes = test::asset_motions();
  REQUIRE(takes.size() == 4);
  for (const std::string& path : takes) require_self_blend(path);
}

TEST_CASE("self-blend reproduces each shared take", "[pipeline]") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  for (const std::string& path : test::shared_motions()) require_self_blend(path);
}

TEST_CASE("bundled pairs: alpha 0 is A, alpha moves steadily to 1, exact bones", "[pipeline]") {
  const std::vector<std::string> takes = test::asset_motions();
  for (const std::string& a : takes)
    for (const std::string& b : takes)
      if (a != b) require_pair(a, b);
}

TEST_CASE("shared pairs within and across conventions", "[pipeline]") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  const std::pair<const char*, const char*> pairs[] = {
      {"bandai_walk_normal.bvh", "bandai_walk_angry.bvh"},
      {"bandai_walk_normal.bvh", "bandai_walk_tired.bvh"},
      {"bandai_walk_old.bvh", "bandai_walk_proud.bvh"},  // 'old' has the other Hips OFFSET
      {"bandai_walk_sad.bvh", "bandai_walk_happy.bvh"},
      {"cmu142_walk_happy.bvh", "cmu142_walk_joy.bvh"},
      {"cmu142_walk_clumsy.bvh", "cmu142_walk_marching.bvh"},
      {"cmu142_walk_marching.bvh", "cmu142_walk_joy.bvh"},
      // Across conventions, units and rates: CMU units at 120 fps against cm at 30 fps.
      {"cmu142_walk_happy.bvh", "bandai_walk_sad.bvh"},
      {"cmu142_walk_marching.bvh", "bandai_walk_proud.bvh"},
      {"bandai_walk_tired.bvh", "cmu142_walk_joy.bvh"},
      {"bandai_walk_angry.bvh", "cmu142_walk_happy.bvh"},  // B 5 times as long as A
  };
  for (const auto& [a, b] : pairs) require_pair(test::shared_motion(a), test::shared_motion(b));
}

TEST_CASE("every ordered pair of shared takes: alpha 0 is A, the pose moves steadily, exact bones",
          "[pipeline]") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  std::map<std::string, std::shared_ptr<const Clip>> clips;
  for (const std::string& path : test::shared_motions()) clips[path] = load(path);
  int pairs = 0;
  for (const auto& [path_a, a] : clips) {
    for (const auto& [path_b, b] : clips) {
      if (path_a == path_b) continue;
      INFO(base_name(path_a) << " + " << base_name(path_b));
      const PairCheck c = check_pair(a, b, {}, false);  // paper mode: in the test above
      INFO("alpha 0: mean " << 100 * c.alpha0.mean << "%, max " << 100 * c.alpha0.max << "%");
      INFO("world distance to alpha 1: " << describe(c.world_to_b));
      INFO("pose distance to alpha 1: " << describe(c.pose_to_b));
      CHECK(c.alpha0.mean < kAlphaZeroMean);
      CHECK(decreasing(c.world_to_b));
      CHECK(decreasing(c.pose_to_b));
      CHECK(c.bones < kBonesExact);
      ++pairs;
    }
  }
  CHECK(pairs == 110);
}

TEST_CASE("shared mode at alpha 1 is B, from A's start", "[pipeline]") {
  const auto a = load(test::asset("motions/cmu142_walk_happy.bvh"));
  const auto b = load(test::asset("motions/cmu142_walk_marching.bvh"));
  const auto p = prepare_takes({a, b}, {});
  const auto d = decompose_takes(*p, reproduction_params());
  const double height = guess_units(*a).height;
  MixParams no_lock;
  no_lock.finish.foot_lock = false;  // compare the synthesis itself
  const MixResult r = blend_at(*p, *d, 1.0, no_lock);
  const Distance e = distance(r.motion.world, sample_rows(p->takes[1].world_placed, r.sources.col(1)), height);
  INFO("alpha 1: mean " << 100 * e.mean << "%, max " << 100 * e.max << "%");
  CHECK(e.mean < kAlphaZeroMean);
  CHECK(e.max < kGrossError);
  // world_b_placed stands where A stands at the start of the match and keeps A's bone lengths.
  const TimeWarp& warp = p->takes[1].alignment.warp;
  const Eigen::MatrixXd b_start = sample_rows(p->takes[1].world_placed, warp.b.head(1));
  const Eigen::MatrixXd a_start = sample_rows(p->takes[0].world, warp.a.head(1));
  CHECK((b_start.block(0, 0, 1, 3) - a_start.block(0, 0, 1, 3)).norm() < 0.05 * height);
  CHECK(relative_bone_error(*p, p->takes[1].world_placed) < kBonesExact);
  CHECK(p->takes[1].world_placed.rows() == p->takes[1].world.rows());
  CHECK(p->takes[1].ground.rows() == p->samples());
}

TEST_CASE("a walk whose start and stop are far longer or shorter than A's plays them whole at weight 1", "[pipeline]") {
  // The angry walk starts 14 frames before its first cycle and stops 3 after its last; the normal
  // walk 2 and 16. At alpha 1 every frame of the angry walk plays, one after another; at alpha 0
  // every frame of the normal one; on A's clock B's longer start is not played at all, so its
  // first output frames do not leap through it.
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  const auto a = load(test::shared_motion("bandai_walk_normal.bvh"));
  const auto b = load(test::shared_motion("bandai_walk_angry.bvh"));
  const auto p = prepare_takes({a, b}, {});
  const auto d = decompose_takes(*p, reproduction_params());
  auto own_frames = [&](const MixResult& r, int take) {
    return frames_in_take(p->takes[static_cast<size_t>(take)], r.sources.col(take));
  };
  auto played_whole = [](const Eigen::VectorXd& frames, Eigen::Index own) {
    double largest_step = 0.0;
    for (Eigen::Index k = 1; k < frames.size(); ++k) largest_step = std::max(largest_step, frames[k] - frames[k - 1]);
    INFO("first " << frames[0] << ", last " << frames[frames.size() - 1] << " of " << own << ", largest step "
                  << largest_step);
    CHECK(frames.allFinite());
    CHECK(frames[0] < 0.5);
    CHECK(frames[frames.size() - 1] > double(own) - 1.5);
    CHECK(largest_step < 1.5);
  };
  const Eigen::Index frames_b = p->takes[1].own_local_t.cols(), frames_a = p->takes[0].own_local_t.cols();
  played_whole(own_frames(blend_at(*p, *d, 1.0), 1), frames_b);
  played_whole(own_frames(blend_at(*p, *d, 0.0), 0), frames_a);
  MixParams on_a;
  on_a.reference_timing = true;
  const Eigen::VectorXd b_on_a = own_frames(blend_at(*p, *d, 1.0, on_a), 1);
  for (Eigen::Index k = 1; k < b_on_a.size(); ++k)
    if (std::isfinite(b_on_a[k]) && std::isfinite(b_on_a[k - 1])) CHECK(b_on_a[k] - b_on_a[k - 1] < 2.5);
}

TEST_CASE("B is retargeted to A's bones across units and frame rates", "[pipeline]") {
  // A: CMU units at 120 fps. B: another take in centimetres at 100 fps.
  const auto a = load(test::asset("motions/cmu142_walk_happy.bvh"));
  const Clip joy = read_bvh_file(test::asset("motions/cmu142_walk_joy.bvh"));
  const auto b = std::make_shared<const Clip>(resample_clip(in_other_units(joy, 5.6444), 100.0));
  REQUIRE(b->fps() == 100.0);
  PrepareOptions whole;  // B's own frames, not registered by cycles
  whole.align.time_base = TimeBase::kWhole;
  const auto p = prepare_takes({a, b}, whole);
  CHECK(p->fps == 30.0);
  CHECK(p->takes[0].world.rows() == resample_clip(*a, 30).frames());
  // B on its own timeline at 30 fps, in A's units and bone lengths.
  CHECK(p->takes[1].world.rows() == resample_clip(*b, 30).frames());
  CHECK(relative_bone_error(*p, p->takes[1].world) < kBonesExact);
  const double hips_a = p->takes[0].world.col(1).mean(), hips_b = p->takes[1].world.col(1).mean();
  CHECK(hips_b / hips_a == Approx(1.0).epsilon(0.1));  // not 5.6 times as high
  // The blend behaves as with the original B.
  const PairCheck scaled = check_pair(a, b);
  const PairCheck original = check_pair(a, load(test::asset("motions/cmu142_walk_joy.bvh")));
  CHECK(scaled.alpha0.mean < kAlphaZeroMean);
  CHECK(decreasing(scaled.world_to_b));
  CHECK(scaled.bones < kBonesExact);
  CHECK(scaled.world_to_b.front() == Approx(original.world_to_b.front()).epsilon(0.15));
}

TEST_CASE("cross-convention pairs: CMU at 120 and 100 fps against Bandai at 30 fps", "[pipeline]") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  const auto cmu = load(test::shared_motion("cmu142_walk_clumsy.bvh"));
  const auto cmu100 = std::make_shared<const Clip>(resample_clip(*cmu, 100.0));
  const auto bandai = load(test::shared_motion("bandai_walk_old.bvh"));
  struct Case {
    const char* name;
    std::shared_ptr<const Clip> a, b;
  };
  const Case cases[] = {{"CMU 120 + Bandai", cmu, bandai},
                        {"CMU 100 + Bandai", cmu100, bandai},
                        {"Bandai + CMU 120", bandai, cmu},
                        {"Bandai + CMU 100", bandai, cmu100}};
  for (const Case& c : cases) {
    INFO(c.name);
    const auto p = prepare_takes({c.a, c.b}, {});
    CHECK(p->majors.size() == 18);  // no hand tips in Bandai
    CHECK(relative_bone_error(*p, p->takes[1].world) < kBonesExact);
    const PairCheck r = check_pair(c.a, c.b);
    INFO("alpha 0: mean " << 100 * r.alpha0.mean << "%, max " << 100 * r.alpha0.max << "%");
    INFO("world distance to alpha 1: " << describe(r.world_to_b));
    CHECK(r.alpha0.mean < kAlphaZeroMean);
    CHECK(decreasing(r.pose_to_b));
    CHECK(decreasing(r.world_to_b));
    CHECK(r.bones < kBonesExact);
  }
}

TEST_CASE("a take turned around walks the other way and blends the same", "[pipeline]") {
  const Clip happy = read_bvh_file(test::asset("motions/cmu142_walk_happy.bvh"));
  const auto a = std::make_shared<const Clip>(happy);
  const auto turned = std::make_shared<const Clip>(turned_around(happy));
  // The turned clip's joints are A's turned by 180 degrees about +Y.
  const Eigen::MatrixXd fk = joint_positions(happy), fk_turned = joint_positions(*turned);
  for (Eigen::Index j = 0; j < fk.cols(); j += 3) {
    CHECK((fk_turned.col(j) + fk.col(j)).cwiseAbs().maxCoeff() < 1e-9);
    CHECK((fk_turned.col(j + 1) - fk.col(j + 1)).cwiseAbs().maxCoeff() < 1e-9);
    CHECK((fk_turned.col(j + 2) + fk.col(j + 2)).cwiseAbs().maxCoeff() < 1e-9);
  }
  SECTION("blended with the original, every alpha is A (the same walk, the other way)") {
    const auto p = prepare_takes({a, turned}, {});
    const auto d = decompose_takes(*p, reproduction_params());
    const Eigen::MatrixXd reference = reference_positions(*a, *p);
    const double height = guess_units(*a).height;
    for (double alpha : kAlphas) {
      const MixResult r = blend_at(*p, *d, alpha);
      const Distance e = distance(r.motion.world, sample_rows(reference, r.sources.col(0)), height);
      INFO("alpha " << alpha << ": mean " << 100 * e.mean << "%, max " << 100 * e.max << "%");
      CHECK(e.mean < kSelfBlendMean);
    }
  }
  SECTION("as A or as B of a pair of styles") {
    const auto joy = load(test::asset("motions/cmu142_walk_joy.bvh"));
    for (const auto& [x, y] : {std::make_pair(turned, joy), std::make_pair(joy, turned)}) {
      const PairCheck r = check_pair(x, y);
      INFO(x->source << " + " << y->source << ": alpha 0 mean " << 100 * r.alpha0.mean << "%");
      INFO("world distance to alpha 1: " << describe(r.world_to_b));
      CHECK(r.alpha0.mean < kAlphaZeroMean);
      CHECK(decreasing(r.world_to_b));
      CHECK(r.bones < kBonesExact);
    }
    // The result of the turned pair is the original pair's, turned around.
    const auto p = prepare_takes({a, joy}, {}), q = prepare_takes({turned, joy}, {});
    const auto dp = decompose_takes(*p, reproduction_params()), dq = decompose_takes(*q, reproduction_params());
    const Eigen::MatrixXd r = blend_at(*p, *dp, 0.5).motion.world, s = blend_at(*q, *dq, 0.5).motion.world;
    Eigen::MatrixXd s_back = s;
    for (Eigen::Index j = 0; j < s.cols(); j += 3) {
      s_back.col(j) = -s.col(j);
      s_back.col(j + 2) = -s.col(j + 2);
    }
    CHECK(distance(s_back, r, guess_units(*a).height).max < 1e-4);
  }
  SECTION("Bandai, turned by its dummy ROOT") {
    MOSTYLE_REQUIRE_SHARED_MOTIONS();
    const Clip sad = read_bvh_file(test::shared_motion("bandai_walk_sad.bvh"));
    const auto sad_turned = std::make_shared<const Clip>(turned_around(sad));
    const auto tired = load(test::shared_motion("bandai_walk_tired.bvh"));
    for (const auto& [x, y] : {std::make_pair(sad_turned, tired), std::make_pair(tired, sad_turned)}) {
      const PairCheck r = check_pair(x, y);
      INFO(x->source << " + " << y->source << ": alpha 0 mean " << 100 * r.alpha0.mean << "%");
      CHECK(r.alpha0.mean < kAlphaZeroMean);
      CHECK(decreasing(r.world_to_b));
    }
  }
}

TEST_CASE("working frame rate: 0 keeps A's", "[pipeline]") {
  const Clip happy = read_bvh_file(test::asset("motions/cmu142_walk_happy.bvh"));
  const auto a = std::make_shared<const Clip>(resample_clip(happy, 24.0));
  const auto b = load(test::asset("motions/cmu142_walk_clumsy.bvh"));
  PrepareOptions o;
  o.fps = 0;
  const auto p = prepare_takes({a, b}, o);
  CHECK(p->fps == 24.0);
  // A's own frames at 24 fps, its cycles played again where B has more (its registration's sources).
  const Eigen::Index own = p->takes[0].registration.empty() ? p->takes[0].world.rows()
                                                             : static_cast<Eigen::Index>(p->takes[0].registration.source.maxCoeff()) + 1;
  CHECK(own == a->frames());
  const PairCheck r = check_pair(a, b, o);
  CHECK(r.alpha0.mean < kAlphaZeroMean);
}

TEST_CASE("mapping overrides reach the pipeline", "[pipeline]") {
  const auto a = load(test::asset("motions/cmu142_walk_happy.bvh"));
  const auto b = load(test::asset("motions/cmu142_walk_joy.bvh"));
  const std::string file = test::asset("mappings/cmu.txt");
  PrepareOptions o;
  o.mapping_a = parse_mapping_overrides(read_file(file), file);
  o.mapping_b = parse_mapping_overrides("left_toe = -\nright_toe = -\n", "no_toes.txt");
  const auto p = prepare_takes({a, b}, o);
  CHECK(p->majors.size() == 18);
  CHECK(major_column(p->majors, static_cast<int>(MajorJoint::kLeftToe)) == -1);
  CHECK(major_column(p->majors, static_cast<int>(MajorJoint::kRightToe)) == -1);
  CHECK(p->takes[0].names.front() == "Hips");
  CHECK(p->takes[1].names[p->feature_joints.left_ankle] == "LeftFoot");
  const auto d = decompose_takes(*p, reproduction_params());
  const MixResult r = blend_at(*p, *d, 0.0);
  const Distance e = distance(r.motion.world, reference_at(*a, *p, r), guess_units(*a).height);
  CHECK(e.mean < kAlphaZeroMean);
}

TEST_CASE("pipeline errors are sentences, not crashes", "[pipeline]") {
  const auto a = load(test::asset("motions/cmu142_walk_happy.bvh"));
  SECTION("a skeleton without knees") {
    test::SkeletonBuilder legs;
    legs.joint("Hips", "", 0, 95, 0)
        .joint("Spine", "Hips", 0, 10, 0)
        .joint("Chest", "Spine", 0, 10, 0)
        .joint("Head", "Chest", 0, 10, 0)
        .joint("LeftUpLeg", "Hips", 9, -5, 0)
        .joint("LeftFoot", "LeftUpLeg", 0, -80, 0)
        .joint("RightUpLeg", "Hips", -9, -5, 0)
        .joint("RightFoot", "RightUpLeg", 0, -80, 0);
    auto b = std::make_shared<Clip>(test::still_clip(legs.skeleton(), 30, 1.0));
    b->source = "stilts.bvh";
    CHECK_THROWS_WITH(prepare_takes({a, b}, {}),
                      Catch::Contains("stilts.bvh: too few major joints") &&
                          Catch::Contains("left_knee (stilts.bvh), right_knee (stilts.bvh)"));
  }
  SECTION("a take without frames") {
    auto b = std::make_shared<Clip>(*a);
    b->motion.resize(0, b->motion.cols());
    b->source = "empty.bvh";
    CHECK_THROWS_WITH(prepare_takes({a, b}, {}), "empty.bvh: has no frames to blend");
  }
  SECTION("bad options and parameters") {
    PrepareOptions o;
    o.fps = -1;
    CHECK_THROWS_AS(prepare_takes({a, a}, o), InputError);
    const auto p = prepare_takes({a, a}, {});
    DecomposeParams d;
    d.components = 0;
    CHECK_THROWS_AS(decompose_takes(*p, d), InputError);
    d = DecomposeParams();
    d.sparsity = 1.5;
    CHECK_THROWS_AS(decompose_takes(*p, d), InputError);
    d = DecomposeParams();
    d.tolerance = -1;
    CHECK_THROWS_AS(decompose_takes(*p, d), InputError);
    d = DecomposeParams();
    d.basic_motions = 2;  // shared mode
    CHECK_THROWS_AS(decompose_takes(*p, d), InputError);
    const auto decomposed = decompose_takes(*p, DecomposeParams());
    test::BlendRun scratch;
    MixResult out;
    CHECK_THROWS_AS(test::blend_into(*p, *decomposed, std::nan(""), MixParams(), scratch, out), InputError);
    CHECK_THROWS_WITH(test::blend_into(*p, *decomposed, 0.5, MixParams(), scratch, out, nullptr, {0.5}),
                      "expected per-component weights of 10 components x 2 takes");
  }
}

TEST_CASE("per-component alphas, limb lengths off, the root pull off", "[pipeline]") {
  const auto a = load(test::asset("motions/cmu142_walk_clumsy.bvh"));
  const auto b = load(test::asset("motions/cmu142_walk_happy.bvh"));
  const auto p = prepare_takes({a, b}, {});
  const auto d = decompose_takes(*p, DecomposeParams());
  SECTION("the same alpha for every component is the plain blend") {
    const std::vector<double> each(d->components(), 0.3);
    CHECK((blend_at(*p, *d, 0.3, MixParams(), each).motion.world - blend_at(*p, *d, 0.3).motion.world).cwiseAbs().maxCoeff() < kSameTake);
  }
  SECTION("without the limb constraint the bones are not exact, and the error says so") {
    MixParams loose;
    loose.finish.limb_lengths = false;
    loose.finish.foot_lock = false;
    const MixResult r = blend_at(*p, *d, 0.5, loose);
    CHECK(relative_bone_error(*p, r.motion.world) > 1e-4);
    CHECK(r.motion.limb_length_max_error == Approx(max_bone_length_error(r.motion.world, p->parents, p->lengths)));
  }
  SECTION("no root pull: alpha 0 is still A") {
    MixParams free;
    free.root_pull_seconds = 0;
    const MixResult r = blend_at(*p, *d, 0.0, free), pulled = blend_at(*p, *d, 0.0);
    CHECK((r.motion.world - pulled.motion.world).cwiseAbs().maxCoeff() < 1e-6);
  }
  SECTION("repeated blends with one scratch give the same result") {
    test::BlendRun scratch;
    MixResult first, again;
    const MixParams bp;
    test::blend_into(*p, *d, 0.7, bp, scratch, first);
    test::blend_into(*p, *d, 0.2, bp, scratch, again);
    test::blend_into(*p, *d, 0.7, bp, scratch, again);
    CHECK(again.motion.world == first.motion.world);
  }
}
