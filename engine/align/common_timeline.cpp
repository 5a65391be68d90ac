#include "engine/align/common_timeline.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/base/error.h"

namespace mostyle {
namespace {

// Reference frames this close to a whole frame are on it.
constexpr double kOnFrame = 1e-9;

// A warp read as a function of the reference's frame, for a reference frame that only grows.
class WarpReader {
 public:
  explicit WarpReader(const TimeWarp& warp) : w_(warp) {}

  // The take's frame at reference frame r (r not below the previous call's).
  double at(double r) {
    seek(r);
    const Eigen::Index last = w_.a.size() - 1;
    if (last == 0) return w_.b[0];
    const double a0 = w_.a[segment_], a1 = w_.a[segment_ + 1];
    const double f = a1 > a0 ? std::clamp((r - a0) / (a1 - a0), 0.0, 1.0) : 1.0;
    return w_.b[segment_] + f * (w_.b[segment_ + 1] - w_.b[segment_]);
  }

  // Where the warp holds the reference at r while the take moves on (its samples there share r:
  // the take plays a part the reference lacks, such as a rest before its action), the take's
  // frame as that hold begins; leaving, at(r) just read, is where it ends. Elsewhere leaving.
  double entering(double r, double leaving) const {
    if (w_.a.size() < 2) return leaving;
    Eigen::Index k = segment_;
    if (std::abs(w_.a[k + 1] - r) <= kOnFrame && w_.a.size() == k + 2) ++k;  // a hold at the warp's end
    if (std::abs(w_.a[k] - r) > kOnFrame) return leaving;
    while (k > 0 && std::abs(w_.a[k - 1] - r) <= kOnFrame) --k;
    return w_.b[k];
  }

  // The largest take frames per reference frame over the segments that meet [r, r + span) (one
  // that starts at r + span is the next stretch's).
  double max_slope(double r, double span) {
    if (r + span < w_.a[0] || r > w_.a[w_.a.size() - 1]) return 0.0;  // held: not moving
    seek(r);
    double slope = 0.0;
    for (Eigen::Index s = segment_; s + 1 < w_.a.size() && w_.a[s] < r + span; ++s) {
      const double da = w_.a[s + 1] - w_.a[s], db = w_.b[s + 1] - w_.b[s];
      if (da > 0) slope = std::max(slope, db / da);
      else if (db > 0) slope = INFINITY;
    }
    return slope;
  }

 private:
  void seek(double r) {
    while (segment_ + 2 < w_.a.size() && w_.a[segment_ + 1] <= r) ++segment_;
  }
  const TimeWarp& w_;
  Eigen::Index segment_ = 0;
};

}  // namespace

CommonTimeline common_timeline(const std::vector<const TimeWarp*>& warps) {
  if (warps.empty()) throw InputError("a palette needs at least two takes");
  for (const TimeWarp* w : warps)
    if (w->samples() == 0) throw InputError("cannot build a common timeline on an empty time warp");
  CommonTimeline t;
  // The union of the matched ranges, with every range's ends as samples.
  std::vector<double> ends;
  for (const TimeWarp* w : warps) {
    ends.push_back(w->a[0]);
    ends.push_back(w->a[w->samples() - 1]);
  }
  std::sort(ends.begin(), ends.end());
  const double first = ends.front(), last = ends.back();
  std::vector<WarpReader> readers;
  for (const TimeWarp* w : warps) readers.emplace_back(*w);
  std::vector<double> reference;
  std::vector<std::vector<double>> takes(warps.size());
  size_t next_end = 0;
  std::vector<double> entering(warps.size()), leaving(warps.size());
  for (double r = first;;) {
    reference.push_back(r);
    double hold = 0.0;
    for (size_t i = 0; i < readers.size(); ++i) {
      leaving[i] = readers[i].at(r);
      entering[i] = readers[i].entering(r, leaving[i]);
      takes[i].push_back(entering[i]);
      hold = std::max(hold, leaving[i] - entering[i]);
    }
    // A hold: the reference stays at r while the takes that hold it there play on, one of their
    // frames a sample at most; the other takes stay where they are.
    const double held = std::ceil(hold - 1e-6);
    for (double p = 1.0; p <= held; p += 1.0) {
      reference.push_back(r);
      for (size_t i = 0; i < readers.size(); ++i)
        takes[i].push_back(entering[i] + (leaving[i] - entering[i]) * p / held);
    }
    if (r >= last) break;
    // The next knot: a range's end or the reference's next whole frame, whichever comes first;
    // the stretch to it split evenly, as finely as the fastest take over it asks.
    while (next_end < ends.size() && ends[next_end] <= r + kOnFrame) ++next_end;
    const double whole = std::floor(r + kOnFrame) + 1.0;
    const double knot = std::min(next_end < ends.size() ? ends[next_end] : last, whole);
    double slope = 1.0;
    for (WarpReader& reader : readers) slope = std::max(slope, reader.max_slope(r, knot - r));
    const double step = std::max(kMinCommonStep, 1.0 / slope);
    const double parts = std::ceil((knot - r) / step - 1e-6);
    r = parts <= 1.0 ? knot : r + (knot - r) / parts;
    if (knot - r <= kOnFrame) r = knot;
  }
  const Eigen::Index samples = static_cast<Eigen::Index>(reference.size());
  t.frames.resize(warps.size() + 1);
  t.frames[0] = Eigen::Map<const Eigen::VectorXd>(reference.data(), samples);
  t.first = {0};
  t.last = {static_cast<int>(samples) - 1};
  for (size_t i = 0; i < takes.size(); ++i) {
    t.frames[i + 1] = Eigen::Map<const Eigen::VectorXd>(takes[i].data(), samples);
    const double a0 = warps[i]->a[0], a1 = warps[i]->a[warps[i]->samples() - 1];
    int f = 0, l = static_cast<int>(samples) - 1;
    while (f < l && reference[static_cast<size_t>(f)] < a0 - 1e-9) ++f;
    while (l > f && reference[static_cast<size_t>(l)] > a1 + 1e-9) --l;
    t.first.push_back(f);
    t.last.push_back(l);
  }
  return t;
}

}  // namespace mostyle
