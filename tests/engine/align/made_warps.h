#pragma once
// Time warps made up for the timeline tests (common timeline, warp position, mixed clock): one
// written out by hand, and random smooth-warp-like ones.
#include <Eigen/Core>
#include <random>
#include <vector>

#include "engine/align/time_warp.h"

namespace mostyle::test {

// The warp with these samples of A's and B's frames.
inline TimeWarp warp_of(std::vector<double> a, std::vector<double> b) {
  TimeWarp w;
  w.a = Eigen::Map<Eigen::VectorXd>(a.data(), static_cast<Eigen::Index>(a.size()));
  w.b = Eigen::Map<Eigen::VectorXd>(b.data(), static_cast<Eigen::Index>(b.size()));
  return w;
}

// A random smooth-warp-like curve: slopes between 1/2 and 2, starting somewhere in 0..10, the
// faster take advancing one frame a sample.
inline TimeWarp random_warp(std::mt19937& rng, int samples) {
  std::uniform_real_distribution<double> start(0.0, 10.0), slope(0.5, 2.0);
  std::vector<double> a{start(rng)}, b{start(rng)};
  for (int s = 1; s < samples; ++s) {
    const double k = slope(rng);
    a.push_back(a.back() + (k > 1 ? 1.0 / k : 1.0));
    b.push_back(b.back() + (k > 1 ? 1.0 : k));
  }
  return warp_of(a, b);
}

}  // namespace mostyle::test
