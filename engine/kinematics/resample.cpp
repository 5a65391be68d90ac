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

// The rotations of every rotating joint at one source frame, as quaternions built straight from
// their Euler angles (Ri(a) Rj(b) Rk(c) is qi(a) qj(b) qk(c)): the half angles' sines and cosines
// in one vectorised pass, no matrix on the way. A sample between two frames slerps two of these,
// and resampling is most of what preparing a take costs.
struct FrameRotations {
  int frame = -1;
  std::vector<Eigen::Quaterniond> q;
};

template <class Motion, class Rotating>
void frame_rotations(const Motion& motion, int frame, const std::vector<Rotating>& rotating,
                     std::vector<double>& halves, std::vector<double>& sines, std::vector<double>& cosines,
                     FrameRotations* out) {
  const size_t n = 3 * rotating.size();
  halves.resize(n);
  sines.resize(n);
  cosines.resize(n);
  for (size_t r = 0; r < rotating.size(); ++r)
    for (int d = 0; d < 3; ++d) halves[3 * r + d] = 0.5 * motion(frame, rotating[r].columns[d]);
  sin_cos_degrees_n(halves.data(), n, sines.data(), cosines.data());
  out->frame = frame;
  out->q.resize(rotating.size());
  for (size_t r = 0; r < rotating.size(); ++r) {
    const auto axes = euler_axes(rotating[r].order);
    // q times (c, s e_k), written out: w' = c w - s v_k, v' = c v + s (w e_k + v x e_k).
    double w = 1.0, v[3] = {0.0, 0.0, 0.0};
    for (int d = 0; d < 3; ++d) {
      const double s = sines[3 * r + d], c = cosines[3 * r + d];
      const int k = axes[d], k1 = (k + 1) % 3, k2 = (k + 2) % 3;
      const double w2 = c * w - s * v[k];
      double v2[3];
      v2[k] = c * v[k] + s * w;
      v2[k1] = c * v[k1] + s * v[k2];
      v2[k2] = c * v[k2] - s * v[k1];
      w = w2;
      for (int i = 0; i < 3; ++i) v[i] = v2[i];
    }
    out->q[r] = Eigen::Quaterniond(w, v[0], v[1], v[2]);
  }
}

}  // namespace

Clip resample_clip(const Clip& clip, double fps, const std::vector<int>& joints) {
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
  return sample_clip(clip, at, fps, joints);
}

Clip sample_clip(const Clip& clip, const Eigen::VectorXd& at, double fps, const std::vector<int>& joints) {
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
  out.motion.setZero(m, clip.motion.cols());
  struct Rotating {
    EulerOrder order;
    int columns[3];  // motion columns of the three rotation channels, in order
  };
  const auto& all = clip.skeleton.joints;
  std::vector<bool> wanted(all.size(), joints.empty());
  if (!joints.empty())
    for (int j : chain_joints(clip.skeleton, joints)) wanted[static_cast<size_t>(j)] = true;
  std::vector<Rotating> rotating;
  std::vector<bool> slerped(clip.motion.cols(), false);  // or not sampled (not wanted)
  for (size_t ji = 0; ji < all.size(); ++ji) {
    const Joint& j = all[ji];
    if (!wanted[ji]) {
      for (size_t c = 0; c < j.channels.size(); ++c) slerped[j.first_channel + c] = true;
      continue;
    }
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

  // Two source frames' rotations kept: upsampling reads each frame for several samples.
  FrameRotations slots[2];
  std::vector<double> halves, sines, cosines;
  auto rotations_at = [&](int frame, int keep) -> const FrameRotations& {
    for (const FrameRotations& s : slots)
      if (s.frame == frame) return s;
    FrameRotations& free = slots[0].frame == keep ? slots[1] : slots[0];
    frame_rotations(clip.motion, frame, rotating, halves, sines, cosines, &free);
    return free;
  };
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
    const FrameRotations* q0s = nullptr;
    const FrameRotations* q1s = nullptr;
    if (!on_source_frame) {
      q0s = &rotations_at(i0, i1);
      q1s = &rotations_at(i1, i0);
    }
    for (size_t ri = 0; ri < rotating.size(); ++ri) {
      const Rotating& r = rotating[ri];
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
        // Eigen's slerp takes the shorter arc (it flips q1 when q0 . q1 < 0).
        const Eigen::Matrix3d m_rot = q0s->q[ri].slerp(w, q1s->q[ri]).toRotationMatrix();
        angles = matrix_to_euler_near(r.order, m_rot, f > 0 ? previous : a0);
      }
      for (int d = 0; d < 3; ++d) out.motion(f, r.columns[d]) = angles[d];
    }
  }
  return out;
}

}  // namespace mostyle
