#pragma once
// Synthetic motion matrices for the decomposition, basic-motion and synthesis tests and benches:
// deterministic (portable generator, fixed seeds), structured like a walk's normalized joints.
#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <random>

namespace mostyle::test {

// Portable random numbers (std::normal_distribution differs between standard libraries).
class Random {
 public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  double gaussian() {
    const double u = 1.0 - uniform();
    const double v = uniform();
    return std::sqrt(-2.0 * std::log(u)) * std::cos(2.0 * M_PI * v);
  }
  Eigen::MatrixXd matrix(Eigen::Index rows, Eigen::Index cols) {
    Eigen::MatrixXd m(rows, cols);
    for (Eigen::Index j = 0; j < cols; ++j)
      for (Eigen::Index i = 0; i < rows; ++i) m(i, j) = gaussian();
    return m;
  }

 private:
  std::mt19937_64 engine_;
};

// frames x 3*joints: `sources` sinusoids (frequency, phase and a second harmonic each), each
// driving a contiguous group of joints along fixed random directions with random amplitudes
// (a limb moving as one), plus Gaussian noise of the given std. Different seeds give different
// motions of the same structure ("styles").
inline Eigen::MatrixXd synthetic_motion(int frames, int joints, int sources, double noise,
                                        std::uint64_t seed) {
  Random random(seed);
  Eigen::MatrixXd x = Eigen::MatrixXd::Zero(frames, 3 * joints);
  for (int s = 0; s < sources; ++s) {
    const double frequency = 2.0 * M_PI * (1.0 + s) / 60.0 * (1.0 + 0.1 * random.uniform());
    const double phase = 2.0 * M_PI * random.uniform();
    const double harmonic = 0.3 * random.gaussian();
    const int first = s * joints / sources;
    const int last = (s + 1) * joints / sources;
    for (int j = first; j < last; ++j) {
      Eigen::Vector3d direction(random.gaussian(), random.gaussian(), random.gaussian());
      direction *= (0.5 + random.uniform()) / direction.norm();
      for (int f = 0; f < frames; ++f) {
        const double t = frequency * f + phase;
        const double signal = std::sin(t) + harmonic * std::sin(2.0 * t + 0.5);
        x.block<1, 3>(f, 3 * j) += signal * direction.transpose();
      }
    }
  }
  if (noise > 0.0) x += noise * random.matrix(frames, 3 * joints);
  return x;
}

// A random-walk series (frames x features): smooth like motion, for alignment tests.
inline Eigen::MatrixXd random_series(Random& random, int frames, int features) {
  Eigen::MatrixXd x(frames, features);
  for (int k = 0; k < features; ++k) {
    double v = 0.0;
    for (int i = 0; i < frames; ++i) x(i, k) = v += random.gaussian();
  }
  return x;
}

}  // namespace mostyle::test
