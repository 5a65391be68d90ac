#pragma once
// The reference's cycles as slots on the common timeline, each take's cycles laid in them
// (cycle_registration.h pair_cycles): a take with fewer cycles than the slots shows some of its
// cycles again in the last ones, the reference too (extend_by_cycles) where another take has
// more. A mix plays the reference's own slots while it has a weight, and as many more as the
// weights give the other takes' own cycles (a walk of 5 cycles blended half and half with one of
// 7 walks 6), and skips the rest, so that each take at weight 1 plays its own cycles once each,
// its start and stop, and none it replays (mixed_clock.h SlotPlay).
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <vector>

namespace mostyle {

struct CycleSlots {
  struct Slot {
    int first = 0, last = 0;  // the common timeline's samples where the slot begins and ends
  };
  std::vector<Slot> slots;  // in order; empty: no take registered by cycles, every sample plays
  // S x N: 1 where slot s shows a cycle of take i for the first time (one of its own), 0 where it
  // shows one again. A loop's every slot is its own (it repeats without end); a take not
  // registered by cycles (its posture only, aligned whole) has the reference's.
  Eigen::MatrixXd own;
  bool empty() const { return slots.empty(); }
  int size() const { return static_cast<int>(slots.size()); }
};

// Slots decided one after another: each slot's share is sum_i w_i own(s, i), within [0, 1], and
// a slot plays where the shares summed so far, rounded, pass the slots played so far. One-hot
// weights play that take's own slots exactly; weights between two takes play a count between
// theirs (round(sum_i w_i n_i)), the slots that more of the weight calls its own first.
class SlotCount {
 public:
  bool play(double share) {
    sum_ += std::clamp(share, 0.0, 1.0);
    if (std::floor(sum_ + 0.5 + 1e-9) <= played_) return false;
    ++played_;
    return true;
  }

 private:
  double sum_ = 0.0;
  int played_ = 0;
};

}  // namespace mostyle
