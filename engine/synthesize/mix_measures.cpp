#include "engine/synthesize/mix_measures.h"

namespace mostyle {
namespace {

std::optional<double> ratio(double value, double of) {
  if (!(of > 0.0)) return std::nullopt;
  return value / of;
}

}  // namespace

std::optional<double> ResultMeasures::planted_ratio() const { return ratio(planted_cleaned, planted_inputs); }
std::optional<double> ResultMeasures::fastest_ratio() const { return ratio(fastest_joint, fastest_inputs); }

MixMeasures mix_measures(const PreparedTakes& prepared, const Decomposed* decomposition, const MixResult* mix,
                         bool finished) {
  MixMeasures m;
  m.body_height = prepared.feet.body_height;
  for (size_t i = 0; i < prepared.takes.size(); ++i) {
    const PreparedTake& take = prepared.takes[i];
    TakeMeasures t;
    if (decomposition != nullptr && i < decomposition->rmse.size()) t.fit_error = decomposition->rmse[i];
    t.planted_speed = take.planted.speed;
    t.fastest_joint = take.fastest_joint;
    m.takes.push_back(t);
  }
  if (mix != nullptr && finished) {
    ResultMeasures r;
    r.limb_length_max_error = mix->motion.limb_length_max_error;
    r.planted_raw = mix->motion.foot_sliding_raw;
    r.planted_cleaned = mix->motion.foot_sliding_cleaned;
    r.planted_inputs = mix->foot_sliding_inputs;
    r.fastest_joint = mix->motion.fastest_joint;
    r.fastest_inputs = mix->fastest_inputs;
    m.result = r;
  }
  return m;
}

}  // namespace mostyle
