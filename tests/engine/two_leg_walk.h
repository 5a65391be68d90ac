#pragma once
// A walk of two legs made up for the foot contact and foot lock tests, in centimetres at kFps: the
// hips move on at kSpeed along +X, each foot planted for kStance frames of every kCycle.
#include <Eigen/Core>
#include <cmath>

#include "engine/measure/foot_contact.h"

namespace mostyle::test {

constexpr double kFps = 30.0;
constexpr double kThigh = 40.0, kShin = 40.0;
constexpr double kHipHeight = 75.0, kAnkleHeight = 8.0;
constexpr double kBodyHeight = 170.0;  // planted within 3% of it (5.1 cm) of a joint's floor
constexpr double kSpeed = 100.0;     // hips, cm/s along +X
constexpr int kCycle = 30;           // frames per step of one foot
constexpr int kStance = 18;          // of which planted

// Columns: left hip, knee, ankle, toe, then the right leg's.
inline FootRig test_rig() {
  FootRig rig;
  rig.legs[0] = {0, 1, 2, 3};
  rig.legs[1] = {4, 5, 6, 7};
  rig.leg_length = kThigh + kShin;
  rig.body_height = kBodyHeight;
  rig.fps = kFps;
  return rig;
}

// The ankles' mean horizontal speed over the steps where `stance` (F x 2) has the foot down at
// both ends, cm/s: how fast the walk's own stance phases slide.
inline double stance_speed(const Eigen::MatrixXd& w, const Eigen::MatrixXd& stance, const FootRig& rig) {
  double sum = 0.0;
  int steps = 0;
  for (int side = 0; side < 2; ++side) {
    const int a = rig.legs[side].ankle;
    for (Eigen::Index t = 0; t + 1 < w.rows(); ++t) {
      if (stance(t, side) <= 0.5 || stance(t + 1, side) <= 0.5) continue;
      sum += std::hypot(w(t + 1, 3 * a) - w(t, 3 * a), w(t + 1, 3 * a + 2) - w(t, 3 * a + 2)) * rig.fps;
      ++steps;
    }
  }
  return steps > 0 ? sum / steps : 0.0;
}

inline Eigen::Vector3d at(const Eigen::MatrixXd& m, Eigen::Index f, int c) {
  return m.block<1, 3>(f, 3 * c).transpose();
}
inline void put(Eigen::MatrixXd& m, Eigen::Index f, int c, const Eigen::Vector3d& v) {
  m.block<1, 3>(f, 3 * c) = v.transpose();
}

// A walk of two legs: hips moving at kSpeed, each foot planted for kStance frames of every
// kCycle (the right half a cycle later), swinging forward with eased motion and a lift in
// between. `skate`: cm/s the planted foot slides forward (a skating blend). The knee bends
// forward (+X) with the thigh and shin lengths fixed; the toe is 12 cm ahead of the ankle.
// planted (out): F x 2, 1 on the planted frames.
inline Eigen::MatrixXd walk(int frames, double skate, Eigen::MatrixXd* planted) {
  Eigen::MatrixXd w(frames, 24);
  planted->setZero(frames, 2);
  for (int side = 0; side < 2; ++side) {
    const double z = side == 0 ? 10.0 : -10.0;
    const int shift = side == 0 ? 0 : kCycle / 2;
    for (int f = 0; f < frames; ++f) {
      const double t = f / kFps;
      const Eigen::Vector3d hip(kSpeed * t, kHipHeight, z);
      // Phase within this foot's cycle; cycle k plants the foot under mid-stance hips.
      const int g = f + shift;
      const int k = g / kCycle, phase = g % kCycle;
      auto plant_x = [&](int cycle) { return kSpeed * ((cycle * kCycle - shift) + kStance / 2.0) / kFps; };
      Eigen::Vector3d ankle;
      if (phase < kStance) {
        ankle = Eigen::Vector3d(plant_x(k) + skate * (phase - kStance / 2.0) / kFps, kAnkleHeight, z);
        (*planted)(f, side) = 1;
      } else {
        const double u = (phase - kStance + 1.0) / (kCycle - kStance + 1.0);  // (0, 1)
        const double from = plant_x(k) + skate * (kStance / 2.0) / kFps;
        const double to = plant_x(k + 1) - skate * (kStance / 2.0) / kFps;
        const double ease = 0.5 - 0.5 * std::cos(M_PI * u);
        const double lift = 12.0 * std::pow(std::sin(M_PI * u), 2);
        ankle = Eigen::Vector3d(from + (to - from) * ease, kAnkleHeight + lift, z);
      }
      // Knee: law of cosines, bent toward +X.
      const Eigen::Vector3d d = ankle - hip;
      const double len = d.norm();
      const Eigen::Vector3d n = d / len;
      const Eigen::Vector3d bend = (Eigen::Vector3d::UnitX() - n * n.x()).normalized();
      const double along = (kThigh * kThigh - kShin * kShin + len * len) / (2 * len);
      const Eigen::Vector3d knee = hip + n * along + bend * std::sqrt(kThigh * kThigh - along * along);
      const int base = 4 * side;
      put(w, f, base, hip);
      put(w, f, base + 1, knee);
      put(w, f, base + 2, ankle);
      put(w, f, base + 3, ankle + Eigen::Vector3d(12, -6, 0));
    }
  }
  return w;
}

}  // namespace mostyle::test
