#pragma once
// A transfer run as `mostyle-cli transfer CONTENT --neutral N --style S --timing content` runs
// it, for tests that hold other paths (the live styler, the export's solve) against it, and the
// fastest joint step of a clip, the measure of a pop.
#include <Eigen/Core>
#include <algorithm>
#include <memory>

#include "engine/align/prepare_takes.h"
#include "engine/base/clip.h"
#include "engine/decompose/decompose_takes.h"
#include "engine/export/export_solve.h"
#include "engine/kinematics/kinematics.h"
#include "engine/synthesize/mix_palette.h"

namespace mostyle::test {

// The transfer of content with timing content, at the content's own rate, its planted feet held to
// the content's, solved onto the content's skeleton (the export's solve).
inline Clip transfer_on_content(const std::shared_ptr<const Clip>& content, const std::shared_ptr<const Clip>& neutral,
                                const std::shared_ptr<const Clip>& style, double strength) {
  PrepareOptions o;
  o.fps = 0.0;  // the content's own rate
  const auto p = prepare_takes({content, neutral, style}, o);
  const auto d = decompose_takes(*p, DecomposeParams());
  MixParams mp;
  mp.layers = transfer_layers({strength});
  mp.min_weight = transfer_min_weight(1);
  mp.max_weight = transfer_max_weight(1);
  mp.reference_timing = true;
  mp.feet_of_reference = true;  // as the command line's transfer holds them
  mp.reference_cycles = true;
  MixScratch scratch;
  MixResult result;
  mix_palette(*p, *d, mp, scratch, result);
  return solve_export_at(*content, export_joints(*p), result.motion.world, source_frames_in_clip(*p, result), p->fps).clip;
}

// The fastest step of any joint (End Sites included) between two frames, from frame `from` on,
// file units.
inline double fastest_joint_step(const Clip& clip, int from = 1) {
  const Eigen::MatrixXd p = joint_positions(clip);
  double fastest = 0.0;
  for (Eigen::Index f = std::max(1, from); f < p.rows(); ++f)
    for (Eigen::Index j = 0; j < p.cols() / 3; ++j)
      fastest = std::max(fastest, (p.block<1, 3>(f, 3 * j) - p.block<1, 3>(f - 1, 3 * j)).norm());
  return fastest;
}

}  // namespace mostyle::test
