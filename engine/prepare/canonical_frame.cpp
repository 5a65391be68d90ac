#include "engine/prepare/canonical_frame.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/base/error.h"
#include "engine/base/simd.h"

namespace mostyle {
namespace {
constexpr double kDegenerateAxis = 1e-12;  // squared hip-axis length on the ground
}

CanonicalMotion to_canonical(const Eigen::MatrixXd& world, int hips, int left_hip, int right_hip) {
  const Eigen::Index frames = world.rows();
  const Eigen::Index joints = world.cols() / 3;
  CanonicalMotion m;
  m.local.resize(frames, world.cols());
  m.ground.resize(frames, 2);
  m.heading.resize(frames);
  double previous = 0.0;
  bool have_previous = false;
  for (Eigen::Index t = 0; t < frames; ++t) {
    // Forward = (left - right) x up, on the ground: (-r.z, 0, r.x).
    const double rx = world(t, 3 * left_hip) - world(t, 3 * right_hip);
    const double rz = world(t, 3 * left_hip + 2) - world(t, 3 * right_hip + 2);
    double heading = previous;
    if (rx * rx + rz * rz > kDegenerateAxis) {
      heading = std::atan2(-rz, rx);
      if (have_previous) heading += 2 * M_PI * std::round((previous - heading) / (2 * M_PI));
      have_previous = true;
    }
    previous = heading;
    m.heading[t] = heading;
  }
  if (frames > 0 && !have_previous)
    throw InputError("the left and right hips coincide on the ground in every frame; no heading");
  // Frames before the first usable axis take its heading.
  for (Eigen::Index t = 0; t < frames; ++t) {
    const double rx = world(t, 3 * left_hip) - world(t, 3 * right_hip);
    const double rz = world(t, 3 * left_hip + 2) - world(t, 3 * right_hip + 2);
    if (rx * rx + rz * rz > kDegenerateAxis) {
      for (Eigen::Index s = 0; s < t; ++s) m.heading[s] = m.heading[t];
      break;
    }
  }
  for (Eigen::Index t = 0; t < frames; ++t) {
    const double gx = world(t, 3 * hips), gz = world(t, 3 * hips + 2);
    m.ground(t, 0) = gx;
    m.ground(t, 1) = gz;
    const double c = std::cos(m.heading[t]), s = std::sin(m.heading[t]);
    for (Eigen::Index j = 0; j < joints; ++j) {
      const double dx = world(t, 3 * j) - gx, dz = world(t, 3 * j + 2) - gz;
      // R_y(-h) (dx, dz): x' = c dx - s dz, z' = s dx + c dz.
      m.local(t, 3 * j) = c * dx - s * dz;
      m.local(t, 3 * j + 1) = world(t, 3 * j + 1);
      m.local(t, 3 * j + 2) = s * dx + c * dz;
    }
  }
  return m;
}

namespace {
// Row `at` (fractional, clamped) of x, linearly interpolated.
Eigen::RowVectorXd row_at(const Eigen::MatrixXd& x, double at) {
  const Eigen::Index last = x.rows() - 1;
  const double t = std::clamp(at, 0.0, double(last));
  const Eigen::Index i = std::min<Eigen::Index>(static_cast<Eigen::Index>(t), std::max<Eigen::Index>(last - 1, 0));
  if (last == 0) return x.row(0);
  const double f = t - double(i);
  return (1 - f) * x.row(i) + f * x.row(i + 1);
}
}  // namespace

PlacedRoot place_at(const CanonicalMotion& a, double a_frame, const CanonicalMotion& b, double b_frame) {
  if (a.ground.rows() == 0 || b.ground.rows() == 0) throw InputError("cannot place a take without frames");
  const Eigen::RowVectorXd ground_a0 = row_at(a.ground, a_frame);
  const Eigen::RowVectorXd ground_b0 = row_at(b.ground, b_frame);
  const double turn = row_at(a.heading, a_frame)(0) - row_at(b.heading, b_frame)(0);
  const double c = std::cos(turn), s = std::sin(turn);
  PlacedRoot placed;
  placed.ground.resize(b.ground.rows(), 2);
  for (Eigen::Index t = 0; t < b.ground.rows(); ++t) {
    const double x = b.ground(t, 0) - ground_b0(0), z = b.ground(t, 1) - ground_b0(1);
    placed.ground(t, 0) = ground_a0(0) + c * x + s * z;
    placed.ground(t, 1) = ground_a0(1) - s * x + c * z;
  }
  placed.heading = b.heading.array() + turn;
  return placed;
}

#ifdef MOSTYLE_HAS_AVX_PATH
namespace {
// to_world's turn of one joint over n frames, four at a time in the same order of operations;
// returns how many frames it placed (a multiple of four).
MOSTYLE_TARGET_AVX Eigen::Index turn_four_at_a_time(const double* c, const double* s, const double* x,
                                                    const double* z, const double* gx, const double* gz,
                                                    Eigen::Index n, double* wx, double* wz) {
  Eigen::Index i = 0;
  for (; i + 4 <= n; i += 4) {
    const __m256d cv = _mm256_loadu_pd(c + i), sv = _mm256_loadu_pd(s + i);
    const __m256d xv = _mm256_loadu_pd(x + i), zv = _mm256_loadu_pd(z + i);
    _mm256_storeu_pd(wx + i, _mm256_add_pd(_mm256_add_pd(_mm256_loadu_pd(gx + i), _mm256_mul_pd(cv, xv)),
                                           _mm256_mul_pd(sv, zv)));
    _mm256_storeu_pd(wz + i, _mm256_add_pd(_mm256_sub_pd(_mm256_loadu_pd(gz + i), _mm256_mul_pd(sv, xv)),
                                           _mm256_mul_pd(cv, zv)));
  }
  return i;
}
}  // namespace
#endif

void to_world(const Eigen::MatrixXd& local, const Eigen::MatrixXd& ground,
              const Eigen::VectorXd& heading, Eigen::MatrixXd* world) {
  const Eigen::Index frames = local.rows(), joints = local.cols() / 3;
  world->resize(frames, local.cols());
  // Blocks of frames, so that every loop runs down contiguous columns (one frame's values lie a
  // column apart in these column-major matrices); the angles of a block are computed once.
  constexpr Eigen::Index kBlock = 64;
  double c[kBlock], s[kBlock];
  [[maybe_unused]] const bool avx = cpu_has_avx();
  for (Eigen::Index first = 0; first < frames; first += kBlock) {
    const Eigen::Index n = std::min(kBlock, frames - first);
    for (Eigen::Index i = 0; i < n; ++i) {
      c[i] = std::cos(heading[first + i]);
      s[i] = std::sin(heading[first + i]);
    }
    for (Eigen::Index j = 0; j < joints; ++j) {
      const double* x = local.col(3 * j).data() + first;
      const double* y = local.col(3 * j + 1).data() + first;
      const double* z = local.col(3 * j + 2).data() + first;
      const double* gx = ground.col(0).data() + first;
      const double* gz = ground.col(1).data() + first;
      double* wx = world->col(3 * j).data() + first;
      double* wy = world->col(3 * j + 1).data() + first;
      double* wz = world->col(3 * j + 2).data() + first;
      Eigen::Index i = 0;
#ifdef MOSTYLE_HAS_AVX_PATH
      if (avx) i = turn_four_at_a_time(c, s, x, z, gx, gz, n, wx, wz);
#endif
      for (; i < n; ++i) {
        wx[i] = gx[i] + c[i] * x[i] + s[i] * z[i];
        wz[i] = gz[i] - s[i] * x[i] + c[i] * z[i];
      }
      std::copy(y, y + n, wy);
    }
  }
}

}  // namespace mostyle
