#include "engine/kinematics/resample.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <string>

#include "engine/kinematics/convert.h"
#include "engine/base/error.h"
#include "engine/kinematics/euler.h"
#include "engine/kinematics/kinematics.h"

namespace mostyle {
namespace {

// The output is a frames x channels matrix of doubles and then text: refuse before allocating
// more than this many values (800 MB).
constexpr double kMaxOutputValues = 100'000'000;
constexpr double kTimeEpsilon = 1e-9;  // frames that land on a source frame up to rounding

std::string number(double v) {
  char buffer[32];
  auto r = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, r.ptr);
}

}  // namespace

Clip resample_clip(const Clip& clip, double fps) {
  if (!(fps > 0.0) || !std::isfinite(fps))
    throw InputError("expected a positive frame rate, found " + number(fps));
  const double source_fps = clip.fps();
  if (!(source_fps > 0.0) || !std::isfinite(source_fps))
    throw InputError(clip.source + ": expected a positive frame time, found " + number(clip.frame_time));
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
  if (!(frames * std::max<double>(1, clip.motion.cols()) <= kMaxOutputValues))
    throw InputError(clip.source + ": resampling " + number(duration) + " s to " + number(fps) +
                     " fps gives " + number(frames) + " frames, too many");
  Eigen::VectorXd at(static_cast<int>(frames));
  for (int f = 0; f < at.size(); ++f) at[f] = std::min(f * source_fps / fps, static_cast<double>(n - 1));
  return sample_clip(clip, at, fps);
}

Clip sample_clip(const Clip& clip, const Eigen::VectorXd& at, double fps) {
  if (!(fps > 0.0) || !std::isfinite(fps))
    throw InputError("expected a positive frame rate, found " + number(fps));
  const int n = clip.frames();
  if (n == 0) throw InputError(clip.source + ": cannot sample a clip with no frames");
  if (!(double(at.size()) * std::max<double>(1, clip.motion.cols()) <= kMaxOutputValues))
    throw InputError(clip.source + ": sampling " + number(double(at.size())) + " frames is too many");
  Clip out;
  out.source = clip.source;
  out.skeleton = clip.skeleton;
  out.frame_time = 1.0 / fps;
  const int m = static_cast<int>(at.size());
  out.motion.resize(m, clip.motion.cols());
  struct Rotating {
    EulerOrder order;
    int columns[3];  // motion columns of the three rotation channels, in order
  };
  std::vector<Rotating> rotating;
  std::vector<bool> slerped(clip.motion.cols(), false);
  for (const Joint& j : clip.skeleton.joints) {
    Rotating r{EulerOrder::kXYZ, {0, 0, 0}};
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
    if (!std::isfinite(at[f])) throw InputError(clip.source + ": cannot sample at a non-finite frame");
    const double u = std::clamp(at[f], 0.0, static_cast<double>(n - 1));
    int i0 = static_cast<int>(std::floor(u + kTimeEpsilon));
    i0 = std::min(i0, n - 1);
    const int i1 = std::min(i0 + 1, n - 1);
    const double w = std::max(0.0, u - i0);
    const bool on_source_frame = w < kTimeEpsilon;
    for (Eigen::Index c = 0; c < clip.motion.cols(); ++c) {
      if (slerped[c]) continue;
      // A frame on a source frame copies it exactly (120 -> 30 is every 4th frame, bit for bit).
      out.motion(f, c) = on_source_frame ? clip.motion(i0, c)
                                         : (1 - w) * clip.motion(i0, c) + w * clip.motion(i1, c);
    }
    for (const Rotating& r : rotating) {
      Eigen::Vector3d a0, previous;
      for (int d = 0; d < 3; ++d) {
        a0[d] = clip.motion(i0, r.columns[d]);
        if (f > 0) previous[d] = out.motion(f - 1, r.columns[d]);
      }
      Eigen::Vector3d angles;
      if (on_source_frame) {
        // The source's own angles, only unwrapped against the previous output frame.
        angles = f > 0 ? euler_near(a0, previous) : a0;
      } else {
        Eigen::Vector3d a1;
        for (int d = 0; d < 3; ++d) a1[d] = clip.motion(i1, r.columns[d]);
        const Eigen::Quaterniond q0(euler_to_matrix(r.order, a0));
        const Eigen::Quaterniond q1(euler_to_matrix(r.order, a1));
        // Eigen's slerp takes the shorter arc (it flips q1 when q0 . q1 < 0).
        const Eigen::Matrix3d m_rot = q0.slerp(w, q1).toRotationMatrix();
        angles = matrix_to_euler_near(r.order, m_rot, f > 0 ? previous : a0);
      }
      for (int d = 0; d < 3; ++d) out.motion(f, r.columns[d]) = angles[d];
    }
  }
  return out;
}

}  // namespace mostyle
