#include "engine/kinematics/limb_length.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/base/error.h"
#include "engine/base/simd.h"
#include "engine/kinematics/joint_rows.h"

namespace mostyle {

namespace {

void check_skeleton(const Eigen::MatrixXd& positions, const std::vector<int>& parents,
                    const char* where) {
  const size_t joints = parents.size();
  if (positions.cols() != static_cast<Eigen::Index>(3 * joints)) {
    throw InputError(std::string(where) + ": positions have " + std::to_string(positions.cols()) +
                     " columns, expected 3 per joint for " + std::to_string(joints) + " joints.");
  }
  for (size_t j = 0; j < joints; ++j) {
    if (parents[j] < -1 || parents[j] >= static_cast<int>(j)) {
      throw InputError(std::string(where) + ": joint " + std::to_string(j) + " has parent " +
                       std::to_string(parents[j]) +
                       "; parents must come before their children (or be -1 for a root).");
    }
  }
}

void check_lengths(const std::vector<int>& parents, const std::vector<double>& lengths,
                   const char* where) {
  if (lengths.size() != parents.size()) {
    throw InputError(std::string(where) + ": " + std::to_string(lengths.size()) +
                     " bone lengths for " + std::to_string(parents.size()) + " joints.");
  }
  for (size_t j = 0; j < lengths.size(); ++j) {
    if (parents[j] >= 0 && !(std::isfinite(lengths[j]) && lengths[j] >= 0.0)) {
      throw InputError(std::string(where) + ": the bone length of joint " + std::to_string(j) +
                       " must be a finite number >= 0, got " + std::to_string(lengths[j]) + ".");
    }
  }
}

// Throws InputError on a skeleton, lengths or options the constraint cannot use.
void check_limb_inputs(const Eigen::MatrixXd& positions, const std::vector<int>& parents,
                       const std::vector<double>& lengths, const LimbLengthOptions& options) {
  check_skeleton(positions, parents, "limb-length constraint");
  check_lengths(parents, lengths, "limb-length constraint");
  if (!(options.degenerate_fraction >= 0.0) || !std::isfinite(options.degenerate_fraction)) {
    throw InputError("limb-length constraint: degenerate_fraction must be a finite number >= 0, "
                     "got " + std::to_string(options.degenerate_fraction) + ".");
  }
  if (!(options.short_fraction >= 0.0) || !(options.short_fraction <= 1.0)) {
    throw InputError("limb-length constraint: short_fraction must be from 0 to 1, got " +
                     std::to_string(options.short_fraction) + ".");
  }
  if (options.fallback_pose.size() != 0 && options.fallback_pose.size() != positions.cols()) {
    throw InputError("limb-length constraint: the fallback pose has " +
                     std::to_string(options.fallback_pose.size()) + " values, expected " +
                     std::to_string(positions.cols()) + ".");
  }
}

// The direction bone j (parent p) of frame f is placed along: its own (bone, child - parent),
// turned gradually from the previous frame's where it is short, the previous frame's where it
// is degenerate, else the fallback pose's or +y. Frame f - 1 of positions is final.
Eigen::Vector3d placed_direction(const Eigen::MatrixXd& positions, Eigen::Index f, int j, int p,
                                 const Eigen::Vector3d& bone, double length, const LimbLengthOptions& options) {
  const double norm = bone.norm();
  Eigen::Vector3d direction;
  const double short_length = options.short_fraction * length;
  if (norm < short_length && f > 0 && length > 0.0) {
    // The previous output frame is final and its bone has length `length` > 0.
    // Turn from the previous direction towards the bone's own by the fraction s of the
    // angle between them: s = (|bone| / short length)^2, so a stub hardly turns and the
    // bone takes its own direction again as it grows back to the short length.
    const Eigen::Vector3d previous = (joint_at(positions, f - 1, j) - joint_at(positions, f - 1, p)) / length;
    const double s = (norm / short_length) * (norm / short_length);
    const double angle = norm > 0.0 ? std::acos(std::clamp(previous.dot(bone / norm), -1.0, 1.0)) : 0.0;
    const double sine = std::sin(angle);
    if (sine > 1e-9)
      direction = (std::sin((1.0 - s) * angle) * previous + std::sin(s * angle) * (bone / norm)) / sine;
    else
      direction = previous;  // the same way, or exactly opposite (no plane to turn in): hold
    direction.normalize();
  } else if (norm > options.degenerate_fraction * length && norm > 0.0) {
    direction = bone * (1.0 / norm);  // one division, not three
  } else if (f > 0 && length > 0.0) {
    // The previous output frame is final and its bone has length `length` > 0.
    direction = (joint_at(positions, f - 1, j) - joint_at(positions, f - 1, p)).normalized();
  } else {
    direction = Eigen::Vector3d::UnitY();
    if (options.fallback_pose.size() != 0) {
      const Eigen::Vector3d reference =
          options.fallback_pose.segment<3>(3 * j).transpose() -
          options.fallback_pose.segment<3>(3 * p).transpose();
      if (reference.norm() > 0.0) direction = reference.normalized();
    }
  }
  return direction;
}

#ifdef MOSTYLE_HAS_AVX_PATH
// Frames [f, f + 4) of a bone placed as placed_direction's plain case places them (the bone's
// own direction, one division), four frames in one: false, with nothing written, where any of
// the four is short or degenerate (placed_direction takes those one at a time).
MOSTYLE_TARGET_AVX bool place_four_own(double* const child[3], const double* const parent[3], Eigen::Index f,
                                       double length, double short_length, double degenerate_length) {
  const __m256d x = _mm256_loadu_pd(child[0] + f), y = _mm256_loadu_pd(child[1] + f), z = _mm256_loadu_pd(child[2] + f);
  const __m256d squared =
      _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(x, x), _mm256_mul_pd(y, y)), _mm256_mul_pd(z, z));
  const __m256d norm = _mm256_sqrt_pd(squared);
  const __m256d own = _mm256_and_pd(
      _mm256_and_pd(_mm256_cmp_pd(norm, _mm256_set1_pd(short_length), _CMP_GE_OQ),
                    _mm256_cmp_pd(norm, _mm256_set1_pd(degenerate_length), _CMP_GT_OQ)),
      _mm256_cmp_pd(norm, _mm256_setzero_pd(), _CMP_GT_OQ));
  if (_mm256_movemask_pd(own) != 0xF) return false;
  const __m256d scale = _mm256_div_pd(_mm256_set1_pd(1.0), norm);
  const __m256d l = _mm256_set1_pd(length);
  const __m256d xs[3] = {x, y, z};
  for (int k = 0; k < 3; ++k) {
    const __m256d direction = _mm256_mul_pd(xs[k], scale);
    _mm256_storeu_pd(child[k] + f, _mm256_add_pd(_mm256_loadu_pd(parent[k] + f), _mm256_mul_pd(l, direction)));
  }
  return true;
}
#endif

}  // namespace

void apply_limb_lengths(Eigen::MatrixXd& positions, const std::vector<int>& parents,
                        const std::vector<double>& lengths, const LimbLengthOptions& options) {
  check_limb_inputs(positions, parents, lengths, options);
  const int joints = static_cast<int>(parents.size());

  // Paper 3.7: restore each bone's reference length from the root outward. Within a frame the
  // row is used as its own scratch, so nothing is allocated: a backward pass turns every
  // non-root joint into its bone vector (child - parent, both still original because parents
  // have lower indices), then a forward pass places child = corrected parent + L * direction.
  // Frames go in blocks so that both passes run down contiguous memory (the matrix is
  // column-major: one frame's values lie a whole column apart); per frame it is the same
  // arithmetic in the same order as one frame at a time, and the previous frame a degenerate
  // bone looks back to is always final (earlier in this joint's loop, or an earlier block).
  constexpr Eigen::Index kBlock = 128;
  const Eigen::Index rows = positions.rows();
  [[maybe_unused]] const bool avx = cpu_has_avx();
  auto column = [&positions, rows](int c) { return positions.data() + rows * static_cast<Eigen::Index>(c); };
  for (Eigen::Index first = 0; first < rows; first += kBlock) {
    const Eigen::Index last = std::min(rows, first + kBlock);
    for (int j = joints - 1; j >= 0; --j) {
      const int p = parents[static_cast<size_t>(j)];
      if (p < 0) continue;
      for (int k = 0; k < 3; ++k) {
        double* child = column(3 * j + k);
        const double* parent = column(3 * p + k);
        for (Eigen::Index f = first; f < last; ++f) child[f] -= parent[f];
      }
    }
    for (int j = 0; j < joints; ++j) {
      const int p = parents[static_cast<size_t>(j)];
      if (p < 0) continue;
      const double length = lengths[static_cast<size_t>(j)];
      double* const child[3] = {column(3 * j), column(3 * j + 1), column(3 * j + 2)};
      const double* const parent_column[3] = {column(3 * p), column(3 * p + 1), column(3 * p + 2)};
      auto place_one = [&](Eigen::Index f) {
        const Eigen::Vector3d bone(child[0][f], child[1][f], child[2][f]);
        const Eigen::Vector3d parent(parent_column[0][f], parent_column[1][f], parent_column[2][f]);
        const Eigen::Vector3d direction = placed_direction(positions, f, j, p, bone, length, options);
        const Eigen::Vector3d placed = parent + length * direction;
        child[0][f] = placed.x();
        child[1][f] = placed.y();
        child[2][f] = placed.z();
      };
      Eigen::Index f = first;
#ifdef MOSTYLE_HAS_AVX_PATH
      if (avx) {  // four frames at once, or those four one at a time
        const double short_length = options.short_fraction * length;
        const double degenerate_length = options.degenerate_fraction * length;
        for (; f + 4 <= last; f += 4)
          if (!place_four_own(child, parent_column, f, length, short_length, degenerate_length))
            for (Eigen::Index g = f; g < f + 4; ++g) place_one(g);
      }
#endif
      for (; f < last; ++f) place_one(f);
    }
  }
}

std::vector<double> bone_lengths(const Eigen::MatrixXd& positions, const std::vector<int>& parents) {
  check_skeleton(positions, parents, "bone lengths");
  if (positions.rows() == 0) throw InputError("bone lengths: the positions have no frames.");
  std::vector<double> lengths(parents.size(), 0.0);
  for (size_t j = 0; j < parents.size(); ++j) {
    const int p = parents[j];
    if (p < 0) continue;
    const auto bones = positions.middleCols(3 * static_cast<Eigen::Index>(j), 3) -
                       positions.middleCols(3 * static_cast<Eigen::Index>(p), 3);
    lengths[j] = bones.rowwise().norm().mean();
  }
  return lengths;
}

double max_bone_length_error(const Eigen::MatrixXd& positions, const std::vector<int>& parents,
                             const std::vector<double>& lengths) {
  check_skeleton(positions, parents, "bone length error");
  check_lengths(parents, lengths, "bone length error");
  double worst = 0.0;
  for (size_t j = 0; j < parents.size(); ++j) {
    const int p = parents[j];
    if (p < 0 || positions.rows() == 0) continue;
    const auto bones = positions.middleCols(3 * static_cast<Eigen::Index>(j), 3) -
                       positions.middleCols(3 * static_cast<Eigen::Index>(p), 3);
    worst = std::max(worst, (bones.rowwise().norm().array() - lengths[j]).abs().maxCoeff());
  }
  return worst;
}

}  // namespace mostyle
