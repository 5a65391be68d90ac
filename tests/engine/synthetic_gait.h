#pragma once
// Made-up legged takes for the contact and cycle tests: a walk, a run with flight phases, a jump
// on both feet, standing; travelling or in place (the planted foot sliding backwards under fixed
// hips, as a game's loop does), cut anywhere in the cycle and at any rate. Nine joints in metres,
// Y up, walking along +Z: hips (the pelvis), then per leg (left at +X) hip, knee, ankle, toe;
// the leg 0.9 m (thigh and shin 0.45 m).
#include <Eigen/Core>
#include <cmath>

#include "engine/align/cycles.h"
#include "engine/measure/foot_contact.h"

namespace mostyle::test {

struct GaitSpec {
  double fps = 30.0;
  double cycle_s = 1.0;    // one cycle: a step of each foot (a jump: one jump)
  double stance = 0.62;    // share of the cycle each foot is planted (a run: under a half)
  double stride = 0.7;     // metres the planted foot travels against the hips
  double lift = 0.12;      // metres the ankle rises in its swing
  bool in_place = false;   // the hips stay (the planted foot slides backwards), else they travel
  bool together = false;   // both feet in step (a jump), else the right half a cycle on
  double crouch = 0.0;     // metres the hips sink at each landing (a jump's)
  double start = 0.0;      // where in the cycle frame 0 is (0: the left foot lands)
  double turn = 0.0;       // radians per cycle the path turns (to the left)
};

constexpr double kGaitThigh = 0.45, kGaitShin = 0.45, kGaitAnkle = 0.08, kGaitHips = 0.84, kGaitHalfWidth = 0.1;

// The rig of a synthetic gait take's columns.
inline FootRig gait_rig(double fps) {
  FootRig rig;
  rig.legs[0] = {1, 2, 3, 4};
  rig.legs[1] = {5, 6, 7, 8};
  rig.leg_length = kGaitThigh + kGaitShin;
  rig.fps = fps;
  return rig;
}

inline GaitJoints gait_joints() {
  GaitJoints j;
  j.hips = 0;
  j.ankles = {3, 7};
  return j;
}

// F x 27 world positions of `frames` frames of the gait.
inline Eigen::MatrixXd gait_take(const GaitSpec& g, int frames) {
  Eigen::MatrixXd w(frames, 27);
  const double pi = 3.14159265358979323846;
  const double travel_speed = g.in_place ? 0.0 : g.stride / (g.stance * g.cycle_s);  // metres per second
  for (int f = 0; f < frames; ++f) {
    const double t = f / g.fps;
    const double cycles = t / g.cycle_s + g.start;
    // The body's path: along its heading, which turns by g.turn per cycle.
    const double heading = g.turn * (cycles - g.start);
    const Eigen::Vector3d forward(std::sin(heading), 0.0, std::cos(heading));
    const Eigen::Vector3d left(std::cos(heading), 0.0, -std::sin(heading));
    Eigen::Vector3d ground = Eigen::Vector3d::Zero();
    if (g.turn == 0.0) {
      ground = forward * travel_speed * t;
    } else {  // an arc of the same speed
      const double radius = travel_speed * g.cycle_s / g.turn;
      ground = Eigen::Vector3d(radius * (1.0 - std::cos(heading)), 0.0, radius * std::sin(heading));
    }
    double sink = 0.0;
    for (int side = 0; side < 2; ++side) {
      const double phase = cycles + (g.together || side == 0 ? 0.0 : 0.5);
      const double p = phase - std::floor(phase);
      if (p < g.stance) sink = std::max(sink, g.crouch * std::sin(pi * p / g.stance));
    }
    const Eigen::Vector3d hips = ground + Eigen::Vector3d(0.0, kGaitHips - sink, 0.0);
    w.block<1, 3>(f, 0) = hips.transpose();
    for (int side = 0; side < 2; ++side) {
      const double phase = cycles + (g.together || side == 0 ? 0.0 : 0.5);
      const double p = phase - std::floor(phase);
      double along, height;  // the ankle against the hips' ground point: forward, and up
      if (p < g.stance) {  // planted: from half a stride ahead to half behind
        along = g.stride * (0.5 - p / g.stance);
        height = kGaitAnkle;
      } else {  // swinging forward, eased, lifted
        const double u = (p - g.stance) / (1.0 - g.stance);
        along = g.stride * (-0.5 + (0.5 - 0.5 * std::cos(pi * u)));
        height = kGaitAnkle + g.lift * std::pow(std::sin(pi * u), 2);
      }
      const double across = side == 0 ? kGaitHalfWidth : -kGaitHalfWidth;
      const Eigen::Vector3d hip = hips + left * across;
      Eigen::Vector3d ankle = ground + forward * along + left * across;
      ankle.y() = height;
      // The knee bends forward (law of cosines); the toe is ahead of the ankle.
      const Eigen::Vector3d d = ankle - hip;
      const double len = std::min(d.norm(), kGaitThigh + kGaitShin - 1e-6);
      const Eigen::Vector3d n = d.normalized();
      const Eigen::Vector3d bend = (forward - n * n.dot(forward)).normalized();
      const double a = (kGaitThigh * kGaitThigh - kGaitShin * kGaitShin + len * len) / (2.0 * len);
      const Eigen::Vector3d knee = hip + n * a + bend * std::sqrt(std::max(0.0, kGaitThigh * kGaitThigh - a * a));
      const Eigen::Vector3d toe = ankle + forward * 0.12 - Eigen::Vector3d(0.0, 0.05, 0.0);
      const int base = 1 + 4 * side;
      w.block<1, 3>(f, 3 * base) = hip.transpose();
      w.block<1, 3>(f, 3 * (base + 1)) = knee.transpose();
      w.block<1, 3>(f, 3 * (base + 2)) = ankle.transpose();
      w.block<1, 3>(f, 3 * (base + 3)) = toe.transpose();
    }
  }
  return w;
}

}  // namespace mostyle::test
