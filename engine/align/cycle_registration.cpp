#include "engine/align/cycle_registration.h"

#include <limits>
#include <string>

#include "engine/io/error.h"

namespace mostyle {

std::vector<int> pair_cycles(const TakeCycles& reference, const TakeCycles& take) {
  std::vector<int> pairs;
  if (take.cycles.empty()) return pairs;
  const int n = static_cast<int>(take.cycles.size());
  for (size_t k = 0; k < reference.cycles.size(); ++k) pairs.push_back(static_cast<int>(k) % n);
  return pairs;
}

Eigen::VectorXd frames_by_cycles(const TakeCycles& reference, const TakeCycles& take, const std::vector<int>& pairs,
                                 int frames) {
  if (pairs.size() != reference.cycles.size())
    throw InputError("cycle registration: expected one matched cycle for each of the reference's " +
                     std::to_string(reference.cycles.size()) + " cycles, found " + std::to_string(pairs.size()));
  Eigen::VectorXd out = Eigen::VectorXd::Constant(frames, std::numeric_limits<double>::quiet_NaN());
  for (size_t k = 0; k < pairs.size(); ++k) {
    const Cycle& r = reference.cycles[k];
    if (pairs[k] < 0 || pairs[k] >= static_cast<int>(take.cycles.size()))
      throw InputError("cycle registration: reference cycle " + std::to_string(k + 1) + " is matched with cycle " +
                       std::to_string(pairs[k] + 1) + " of a take that has " + std::to_string(take.cycles.size()));
    if (r.begin < 0 || r.end > frames || r.end <= r.begin)
      throw InputError("cycle registration: reference cycle " + std::to_string(k + 1) + " (frames " +
                       std::to_string(r.begin) + " to " + std::to_string(r.end) + ") is not within its " +
                       std::to_string(frames) + " frames");
    const Cycle& t = take.cycles[static_cast<size_t>(pairs[k])];
    const double scale = double(t.frames()) / double(r.frames());
    for (int f = r.begin; f < r.end; ++f) out[f] = t.begin + (f - r.begin) * scale;
  }
  return out;
}

}  // namespace mostyle
