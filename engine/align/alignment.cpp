#include "engine/align/alignment.h"

#include <algorithm>
#include <cmath>
#include <array>
#include <cstdio>

#include "engine/base/error.h"

namespace mostyle {
namespace {

std::string seconds(double frames, double fps) {
  char s[32];
  std::snprintf(s, sizeof s, "%.1f s", frames / fps);
  return s;
}

double median(Eigen::VectorXd v) {
  if (v.size() == 0) return 0.0;
  auto mid = v.data() + v.size() / 2;
  std::nth_element(v.data(), mid, v.data() + v.size());
  return *mid;
}

// Per-sample quality, the poor stretches and the warnings.
void assess(Alignment& al, int frames_a, int frames_b, double fps) {
  const TimeWarp& w = al.warp;
  const int u = w.samples();
  const Eigen::MatrixXd fa = sample_rows(al.feature.a, w.a), fb = sample_rows(al.feature.b, w.b);
  const Eigen::VectorXd cost = (fa - fb).rowwise().norm();
  al.typical_cost = median(cost);
  const double typical = al.typical_cost > 0 ? al.typical_cost : std::max(cost.maxCoeff(), 1e-300);
  al.cost_ratio = cost / typical;
  al.slope.resize(u);
  for (int k = 0; k < u; ++k) {
    const int lo = std::max(0, k - 1), hi = std::min(u - 1, k + 1);
    const double da = w.a[hi] - w.a[lo], db = w.b[hi] - w.b[lo];
    al.slope[k] = da > 1e-12 ? db / da : (db > 0 ? 1e9 : 1.0);
  }
  const int min_run = std::max(1, static_cast<int>(std::lround(kPoorMatchSeconds * fps)));
  for (int k = 0; k < u;) {
    if (al.cost_ratio[k] <= kPoorMatchRatio) {
      ++k;
      continue;
    }
    int end = k;
    while (end + 1 < u && al.cost_ratio[end + 1] > kPoorMatchRatio) ++end;
    if (end - k + 1 >= min_run) al.poor.emplace_back(k, end);
    k = end + 1;
  }
  al.frames_a = frames_a;
  al.frames_b = frames_b;
  al.warnings = alignment_warnings(al, fps, {"A", 0.0}, {"B", 0.0});
}

// A piece of the structure path: frames [a0, a1] of A onto [b0, b1] of B, inclusive.
struct PathPiece {
  int a0, a1, b0, b1;
  bool dtw;  // matched by DTW (the moving spans), else a straight line (rests, holds)
};

// The three pieces (rest, action, rest) of each take as frame knots: 0, action begin, action
// end (last moving frame), last frame.
std::array<int, 4> structure_knots(const ActionSpans& s, int frames) {
  if (s.still()) return {0, 0, frames - 1, frames - 1};
  const FrameSpan active = s.active();
  return {0, active.begin, std::max(active.begin, active.end - 1), frames - 1};
}

std::string span_words(int first, int last, double fps) {
  char s[64];
  std::snprintf(s, sizeof s, "%.1f-%.1f s", first / fps, (last + 1) / fps);
  return s;
}

// The pieces of the structure path, and what they hold or leave out.
std::vector<PathPiece> structure_pieces(const ActionSpans& sa, int fa, const ActionSpans& sb, int fb, double fps,
                                        std::vector<std::string>* notes) {
  std::vector<PathPiece> pieces;
  if (sa.still() || sb.still()) {
    // A take at rest throughout: the whole of A onto B's rest before, or B's whole take.
    if (sa.still() && !sb.still()) {
      // B's action (and the rest after it) plays while A holds its last pose: all of B at weight 1.
      const int rest = sb.rest_before > 0 ? sb.rest_before - 1 : 0;
      pieces.push_back({0, fa - 1, 0, rest, false});
      pieces.push_back({fa - 1, fa - 1, rest, fb - 1, false});
      notes->push_back(std::string("A is at rest throughout: ") +
                       (sb.rest_before > 0 ? "it is matched with B's rest before its action, then holds"
                                           : "it holds") +
                       " its last pose while B's action (" + span_words(sb.active().begin, sb.active().end - 1, fps) +
                       ") plays");
    } else {
      pieces.push_back({0, fa - 1, 0, fb - 1, !sa.still()});
      if (sb.still() && !sa.still())
        notes->push_back("B is at rest throughout: its rest is laid on the whole of A's action");
    }
    return pieces;
  }
  const std::array<int, 4> ka = structure_knots(sa, fa), kb = structure_knots(sb, fb);
  const char* where[3] = {"before", "", "after"};
  for (int k = 0; k < 3; ++k) {
    PathPiece piece{ka[k], ka[k + 1], kb[k], kb[k + 1], k == 1};
    const bool a_has = ka[k + 1] > ka[k], b_has = kb[k + 1] > kb[k];
    if (k != 1 && a_has && !b_has)
      notes->push_back(std::string("B has no rest ") + where[k] + " its action: it holds its " +
                       (k == 0 ? "first" : "last") + " pose over A's rest (" + span_words(ka[k], ka[k + 1], fps) + ")");
    if (k != 1 && !a_has && b_has)
      notes->push_back(std::string("A has no rest ") + where[k] + " its action: it holds its " +
                       (k == 0 ? "first" : "last") + " pose while B's (" + span_words(kb[k], kb[k + 1], fps) +
                       ") plays");
    pieces.push_back(piece);
  }
  return pieces;
}

}  // namespace

std::vector<std::string> alignment_warnings(const Alignment& al, double fps, const AlignedTake& a, const AlignedTake& b) {
  // A frame at the working rate as its file counts it.
  auto in_file = [&](double frame, const AlignedTake& take) {
    return static_cast<int>(std::lround(take.file_fps > 0 ? frame * take.file_fps / fps : frame));
  };
  // B's frames as the take's own (by cycles, B's frames are the registered take's).
  auto b_own = [&](double frame) {
    if (!al.by_cycles()) return frame;
    const Eigen::Index at = std::clamp<Eigen::Index>(std::lround(frame), 0, al.b_source.size() - 1);
    return std::isnan(al.b_source[at]) ? frame : al.b_source[at];
  };
  const TimeWarp& w = al.warp;
  std::vector<std::string> out;
  for (const auto& [k, end] : al.poor) {
    char s[512];
    std::snprintf(s, sizeof s,
                  "%s's frames %d-%d (%s to %s) match %s's frames %d-%d poorly: the %s differ %.1f times as much as "
                  "along the rest of the alignment",
                  a.name.c_str(), in_file(w.a[k], a), in_file(w.a[end], a), seconds(w.a[k], fps).c_str(),
                  seconds(w.a[end], fps).c_str(), b.name.c_str(), in_file(b_own(w.b[k]), b), in_file(b_own(w.b[end]), b),
                  align_on_name(al.feature.on), al.cost_ratio.segment(k, end - k + 1).mean());
    out.push_back(s);
  }
  auto left_out = [&](const AlignedTake& take, int first, int last, int frames, const AlignedTake& other) {
    const int matched = last - first + 1;
    if (matched >= kMatchedFractionWarning * frames) return;
    char s[512];
    std::snprintf(s, sizeof s, "only %s's frames %d-%d (%s of %s) match %s; the rest is left out", take.name.c_str(),
                  in_file(first, take), in_file(last, take), seconds(matched, fps).c_str(), seconds(frames, fps).c_str(),
                  other.name == "A" || other.name == "B" ? "the other take" : other.name.c_str());
    out.push_back(s);
  };
  left_out(a, al.a_first, al.a_last, al.frames_a, b);
  left_out(b, al.b_first, al.b_last, al.frames_b, a);
  return out;
}

const char* time_base_name(TimeBase base) { return base == TimeBase::kCycles ? "cycles" : "whole"; }

TimeBase parse_time_base(const std::string& name) {
  if (name == "cycles") return TimeBase::kCycles;
  if (name == "whole") return TimeBase::kWhole;
  throw InputError("expected a time base cycles or whole, found '" + name + "'");
}

const char* dtw_method_name(DtwMethod method) { return method == DtwMethod::kSlope ? "slope" : "paper"; }

DtwMethod parse_dtw_method(const std::string& name) {
  if (name == "slope") return DtwMethod::kSlope;
  if (name == "paper") return DtwMethod::kPaper;
  throw InputError("expected a DTW method slope or paper, found '" + name + "'");
}

void AlignmentOptions::Validate() const {
  if (band < -1) throw InputError("expected a DTW band of 0 or more frames, found " + std::to_string(band));
  slope.Validate();
  if (!(smoothing_frames >= 0) || !std::isfinite(smoothing_frames))
    throw InputError("expected a warp smoothing of 0 or more frames");
}

Alignment align_takes(const CanonicalMotion& a, const CanonicalMotion& b, const FeatureJoints& joints,
                      double leg_length, double fps, const AlignmentOptions& options, JobControl* control) {
  options.Validate();
  Alignment al;
  al.options = options;
  const bool paper = options.method == DtwMethod::kPaper;
  al.feature = alignment_feature(a, b, joints, paper ? AlignOn::kLeftFoot : options.on, leg_length, fps);
  const int frames_a = static_cast<int>(a.local.rows()), frames_b = static_cast<int>(b.local.rows());
  if (paper) {
    DtwOptions o;
    o.band = options.band;
    const DtwPath path = align_dtw(al.feature.a, al.feature.b, o, control);
    al.path = path.steps;
    al.cost = path.cost;
    al.warp = paper_warp(path, frames_a);
  } else {
    const SlopeDtwPath path = align_slope_dtw(al.feature.a, al.feature.b, options.slope, control);
    al.path = path.steps;
    al.cost = path.cost;
    al.end_penalty = path.end_penalty;
    al.warp = smooth_warp(path.steps, options.smoothing_frames);
  }
  al.a_first = al.path.front().first;
  al.a_last = al.path.back().first;
  al.b_first = al.path.front().second;
  al.b_last = al.path.back().second;
  assess(al, frames_a, frames_b, fps);
  return al;
}

Alignment align_by_cycles(const CanonicalMotion& a, const RegisteredMotion& b, const FeatureJoints& joints,
                          double leg_length, double fps, const AlignmentOptions& options, JobControl* control) {
  options.Validate();
  const std::vector<CycleRegistration::Anchor>& anchors = b.registration.anchors;
  if (anchors.size() < 2) throw InputError("cycle registration: a registered take needs its spans' anchors");
  Alignment al;
  al.options = options;
  al.feature = alignment_feature(a, b.motion, joints, options.on, leg_length, fps);
  const Eigen::MatrixXd& fa = al.feature.a;
  const Eigen::MatrixXd& fb = al.feature.b;
  // A hold at either end (a start or stop far longer in one take) is kept apart from the rest of
  // the path, so that smoothing does not turn it into a ramp on which the take that plays runs
  // several times its speed on the other's clock.
  std::vector<std::pair<int, int>> lead, middle, tail;
  std::vector<std::pair<int, int>>* piece = &middle;
  auto add = [&](int i, int j) {
    if (piece->empty() || piece->back() != std::make_pair(i, j)) piece->emplace_back(i, j);
    if (al.path.empty() || al.path.back() != std::make_pair(i, j)) al.path.emplace_back(i, j);
  };
  SlopeDtwOptions closed = options.slope;
  closed.open_ends = false;
  for (size_t s = 0; s + 1 < anchors.size(); ++s) {
    const bool at_end = s == 0 || s + 2 == anchors.size();
    piece = anchors[s].hold && at_end && anchors.size() > 2 ? (s == 0 ? &lead : &tail) : &middle;
    check_cancel(control);
    const int r0 = anchors[s].reference, v0 = anchors[s].registered;
    const int n = anchors[s + 1].reference - r0, m = anchors[s + 1].registered - v0;
    if (anchors[s].hold) {  // one of the two stays at its frame while the other plays on
      for (int k = 0; k <= std::max(n, m); ++k) {
        const int i = r0 + std::min(k, n), j = v0 + std::min(k, m);
        add(i, j);
        al.cost += (fa.row(i) - fb.row(j)).norm();
      }
      continue;
    }
    if (!anchors[s].cycle) {  // between cycles, 1:1
      for (int j = 0; j <= n; ++j) {
        add(r0 + j, v0 + j);
        al.cost += (fa.row(r0 + j) - fb.row(v0 + j)).norm();
      }
      continue;
    }
    // A cycle and its match: the slope-limited DTW with closed ends, or a line when the lengths
    // are too far apart for its slope.
    try {
      const SlopeDtwPath path = align_slope_dtw(fa.middleRows(r0, n + 1), fb.middleRows(v0, m + 1), closed, control);
      for (const auto& [i, j] : path.steps) add(r0 + i, v0 + j);
      al.cost += path.cost;
    } catch (const InputError&) {
      const int steps = std::max(n, m);
      for (int k = 0; k <= steps; ++k) add(r0 + static_cast<int>(std::lround(double(k) * n / steps)),
                                          v0 + static_cast<int>(std::lround(double(k) * m / steps)));
    }
  }
  // Smoothed over a part of a cycle: a warp that bends sharply within a cycle plays one take's
  // frames up to max_slope times as fast for a moment, which a mix with negative weights (a
  // transfer) makes visible as a burst of speed.
  const double smoothing = std::max(options.smoothing_frames, kCycleWarpSmoothing * b.registration.cycles.period);
  std::vector<TimeWarp> warps;
  if (lead.size() > 1) warps.push_back(smooth_warp(lead, 0.0));
  warps.push_back(smooth_warp(middle, smoothing));
  if (tail.size() > 1) warps.push_back(smooth_warp(tail, 0.0));
  al.warp = joined_warps(warps);
  const int lead_samples = lead.size() > 1 ? warps.front().samples() : 0;
  const int tail_samples = tail.size() > 1 ? warps.back().samples() : 0;
  // What a hold does, said as the structure alignment says it of rests.
  auto lasting = [&](int frames) {
    char s[32];
    std::snprintf(s, sizeof s, "%.1f s", frames / fps);
    return std::string(s);
  };
  if (lead_samples > 0) {
    const int a_frames = lead.back().first - lead.front().first, b_frames = lead.back().second - lead.front().second;
    al.notes.push_back(a_frames == 0 ? "B's start is longer than A's: A holds its first pose while B's first " +
                                           lasting(b_frames) + " play (none of them on A's clock)"
                                     : "A's start is longer than B's: B holds its first pose over A's first " +
                                           lasting(a_frames));
  }
  if (tail_samples > 0) {
    const int a_frames = tail.back().first - tail.front().first, b_frames = tail.back().second - tail.front().second;
    al.notes.push_back(a_frames == 0 ? "B's stop is longer than A's: A holds its last pose while B's last " +
                                           lasting(b_frames) + " play (none of them on A's clock)"
                                     : "A's stop is longer than B's: B holds its last pose over A's last " +
                                           lasting(a_frames) + " (none of them at B's weight 1)");
  }
  al.a_first = 0;
  al.a_last = anchors.back().reference;
  al.b_first = 0;
  al.b_last = anchors.back().registered;
  al.b_source = b.registration.source;
  assess(al, static_cast<int>(a.local.rows()), static_cast<int>(b.motion.local.rows()), fps);
  // A held pose against one that moves matches poorly by construction; the notes say why.
  const int samples = al.warp.samples();
  al.poor.erase(std::remove_if(al.poor.begin(), al.poor.end(),
                               [&](const std::pair<int, int>& p) {
                                 return p.first < lead_samples || p.second >= samples - tail_samples;
                               }),
                al.poor.end());
  return al;
}

Alignment align_by_structure(const CanonicalMotion& a, const ActionSpans& a_spans, const CanonicalMotion& b,
                             const ActionSpans& b_spans, const FeatureJoints& joints, double leg_length, double fps,
                             const AlignmentOptions& options, JobControl* control) {
  options.Validate();
  const int fa = static_cast<int>(a.local.rows()), fb = static_cast<int>(b.local.rows());
  if (a_spans.frames != fa || b_spans.frames != fb || fa < 1 || fb < 1)
    throw InputError("structure alignment: the takes' rests and actions were read on other frames than the takes'");
  Alignment al;
  al.options = options;
  al.by_structure = true;
  al.feature = alignment_feature(a, b, joints, options.on, leg_length, fps);
  const Eigen::MatrixXd& ea = al.feature.a;
  const Eigen::MatrixXd& eb = al.feature.b;
  auto add = [&](int i, int j) {
    if (!al.path.empty() && al.path.back() == std::make_pair(i, j)) return;
    al.path.emplace_back(i, j);
  };
  SlopeDtwOptions closed = options.slope;
  closed.open_ends = false;
  for (const PathPiece& p : structure_pieces(a_spans, fa, b_spans, fb, fps, &al.notes)) {
    check_cancel(control);
    // A part of B that A lacks (n == 0) is a hold of A: the common timeline gives it B's time at
    // B's weight, none on A's clock.
    const int n = p.a1 - p.a0, m = p.b1 - p.b0;
    if (p.dtw && n > 0 && m > 0) {
      try {
        const SlopeDtwPath path = align_slope_dtw(ea.middleRows(p.a0, n + 1), eb.middleRows(p.b0, m + 1), closed, control);
        for (const auto& [i, j] : path.steps) add(p.a0 + i, p.b0 + j);
        al.cost += path.cost;
        continue;
      } catch (const InputError&) {
        // Lengths too far apart for the slope limit: the straight line below.
      }
    }
    const int steps = std::max(n, m);
    for (int k = 0; k <= steps; ++k)
      add(p.a0 + (steps > 0 ? static_cast<int>(std::lround(double(k) * n / steps)) : 0),
          p.b0 + (steps > 0 ? static_cast<int>(std::lround(double(k) * m / steps)) : 0));
  }
  al.warp = smooth_warp(al.path, options.smoothing_frames);
  al.a_first = al.path.front().first;
  al.a_last = al.path.back().first;
  al.b_first = al.path.front().second;
  al.b_last = al.path.back().second;
  assess(al, fa, fb, fps);
  return al;
}

}  // namespace mostyle
