#include "engine/resample.h"

#include <Eigen/Geometry>
#include <cmath>
#include <string>

#include "engine/convert.h"
#include "engine/error.h"
#include "engine/euler.h"
#include "engine/kinematics.h"

namespace mostyle {
namespace {
constexpr double kMaxOutputFrames = 50'000'000;
constexpr double kTimeEpsilon = 1e-9;  // frames that land on a source frame up to rounding
}  // namespace

Clip resample_clip(const Clip& clip, double fps) {
  if (!(fps > 0.0) || !std::isfinite(fps))
    throw InputError("expected a positive frame rate, found " + std::to_string(fps));
  const double source_fps = clip.fps();
  Clip out;
  out.source = clip.source;
  out.skeleton = clip.skeleton;
  out.frame_time = 1.0 / fps;
  const int n = clip.frames();
  if (n == 0) {
    out.motion.resize(0, clip.motion.cols());
    return out;
  }
  const double duration = (n - 1) / source_fps;
  const double frames = std::floor(duration * fps + kTimeEpsilon) + 1;
  if (frames > kMaxOutputFrames)
    throw InputError(clip.source + ": resampling to " + std::to_string(fps) + " fps gives too many frames");
  const int m = static_cast<int>(frames);
  out.motion.resize(m, clip.motion.cols());

  struct Rotating {
    const Joint* joint;
    EulerOrder order;
    int columns[3];  // motion columns of the three rotation channels, in order
  };
  std::vector<Rotating> rotating;
  std::vector<bool> slerped(clip.motion.cols(), false);
  for (const Joint& j : clip.skeleton.joints) {
    Rotating r{&j, EulerOrder::kXYZ, {0, 0, 0}};
    if (j.end_site || !joint_euler_order(j, &r.order)) continue;
    int k = 0;
    for (size_t c = 0; c < j.channels.size(); ++c) {
      if (is_rotation(j.channels[c])) {
        r.columns[k++] = j.first_channel + static_cast<int>(c);
        slerped[j.first_channel + c] = true;
      }
    }
    rotating.push_back(r);
  }

  for (int f = 0; f < m; ++f) {
    const double u = std::min(f * source_fps / fps, static_cast<double>(n - 1));
    int i0 = static_cast<int>(std::floor(u + kTimeEpsilon));
    i0 = std::min(i0, n - 1);
    const int i1 = std::min(i0 + 1, n - 1);
    const double w = std::max(0.0, u - i0);
    for (Eigen::Index c = 0; c < clip.motion.cols(); ++c) {
      if (!slerped[c]) out.motion(f, c) = (1 - w) * clip.motion(i0, c) + w * clip.motion(i1, c);
    }
    for (const Rotating& r : rotating) {
      Eigen::Vector3d a0, a1;
      for (int d = 0; d < 3; ++d) {
        a0[d] = clip.motion(i0, r.columns[d]);
        a1[d] = clip.motion(i1, r.columns[d]);
      }
      Eigen::Vector3d angles;
      if (w < kTimeEpsilon) {
        angles = a0;
      } else {
        const Eigen::Quaterniond q0(euler_to_matrix(r.order, a0));
        const Eigen::Quaterniond q1(euler_to_matrix(r.order, a1));
        const Eigen::Matrix3d m_rot = q0.slerp(w, q1).toRotationMatrix();
        // Keep the curve continuous with the source's own branch at i0.
        angles = matrix_to_euler_near(r.order, m_rot, a0);
      }
      if (f > 0) {
        Eigen::Vector3d previous;
        for (int d = 0; d < 3; ++d) previous[d] = out.motion(f - 1, r.columns[d]);
        angles = matrix_to_euler_near(r.order, euler_to_matrix(r.order, angles), previous);
      }
      for (int d = 0; d < 3; ++d) out.motion(f, r.columns[d]) = angles[d];
    }
  }
  return out;
}

}  // namespace mostyle
