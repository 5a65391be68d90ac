#include "ui/model/cycle_provenance.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <limits>
#include <map>

#include "engine/align/prepare_takes.h"

namespace mostyle::ui {
namespace {

// The cycles cycles_shown indexes: those the take was registered with, else as detected.
const TakeCycles& own_cycles(const PreparedTake& take) {
  return take.registration.empty() ? take.cycles : take.registration.take_cycles;
}

// Frames of the take's file at its own rate per frame at the working rate (as mix_palette.cpp
// source_frames_in_clip); 1 without a clip (a take made by hand).
double file_rate_ratio(const PreparedTake& take, double working_fps) {
  return take.clip != nullptr && working_fps > 0.0 ? take.clip->fps() / working_fps : 1.0;
}

int file_frame(double working_frame, double ratio) { return static_cast<int>(std::lround(working_frame * ratio)); }

// What take i shows over output frames [begin, end): shown and frames are its cycles_shown and
// frames_in_take over the whole output (K). The cycle shown at most of the span's frames (the
// first met of a tie); when that is none, its file's frames shown outside its cycles, or its
// posture only when most of those frames have none.
TakeCycleSource source_in_span(const PreparedTake& take, double fps, const Eigen::VectorXi& shown,
                               const Eigen::VectorXd& frames, int begin, int end) {
  TakeCycleSource s;
  std::map<int, int> count;
  int most = -1, most_count = 0;
  for (int k = begin; k < end; ++k) {
    const int c = ++count[shown[k]];
    if (c > most_count) {
      most = shown[k];
      most_count = c;
    }
  }
  const std::vector<Cycle>& cycles = own_cycles(take).cycles;
  const double ratio = file_rate_ratio(take, fps);
  if (most >= 0 && most < static_cast<int>(cycles.size())) {
    const Cycle& c = cycles[static_cast<size_t>(most)];
    s.kind = CycleSourceKind::kCycle;
    s.cycle = most;
    s.first_frame = file_frame(c.begin, ratio);
    s.last_frame = std::max(s.first_frame, file_frame(c.end, ratio) - 1);  // [begin, end): end starts what follows
    s.begin_s = c.begin / fps;
    s.end_s = c.end / fps;
    return s;
  }
  // Outside its cycles: the frames it shows there, unless most have none (its posture only).
  int none = 0, some = 0;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (int k = begin; k < end; ++k) {
    if (shown[k] >= 0) continue;
    if (!std::isfinite(frames[k])) {
      ++none;
      continue;
    }
    ++some;
    lo = std::min(lo, frames[k]);
    hi = std::max(hi, frames[k]);
  }
  if (some == 0 || none > some) return s;  // kPostureOnly
  s.kind = CycleSourceKind::kOutsideCycles;
  s.first_frame = file_frame(lo, ratio);
  s.last_frame = file_frame(hi, ratio);
  s.begin_s = lo / fps;
  s.end_s = hi / fps;
  return s;
}

}  // namespace

std::vector<CycleProvenance> cycle_provenance(const PreparedTakes& prepared, const Eigen::MatrixXd& sources,
                                              const std::vector<std::string>& names) {
  const int n = prepared.size();
  assert(sources.cols() == n && "cycle_provenance: one column of sources per take");
  std::vector<CycleProvenance> spans;
  const int frames = static_cast<int>(sources.rows());
  if (frames == 0 || n == 0 || sources.cols() != n) return spans;
  const double fps = prepared.fps > 0.0 ? prepared.fps : 30.0;
  std::vector<Eigen::VectorXi> shown(static_cast<size_t>(n));
  std::vector<Eigen::VectorXd> own(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    const PreparedTake& take = prepared.takes[static_cast<size_t>(i)];
    shown[static_cast<size_t>(i)] = cycles_shown(take, sources.col(i));
    own[static_cast<size_t>(i)] = frames_in_take(take, sources.col(i));
  }
  // The spans: runs of output frames where the reference shows one of its timeline's cycles (a
  // slot: its own cycle, or one played again where another take has more), or none.
  const std::vector<Cycle>& slots = prepared.takes.front().timeline_cycles().cycles;
  Eigen::VectorXi reference(frames);
  for (int k = 0; k < frames; ++k) {
    const double f = sources(k, 0);
    const auto at = std::upper_bound(slots.begin(), slots.end(), f, [](double x, const Cycle& c) { return x < c.begin; });
    reference[k] = at != slots.begin() && f < std::prev(at)->end ? static_cast<int>(std::prev(at) - slots.begin()) : -1;
  }
  int output_cycle = 0;
  for (int begin = 0; begin < frames;) {
    int end = begin + 1;
    while (end < frames && reference[end] == reference[begin]) ++end;
    CycleProvenance span;
    span.begin = begin;
    span.end = end;
    span.cycle = reference[begin] >= 0 ? output_cycle++ : -1;
    span.slot = reference[begin];
    spans.push_back(std::move(span));
    begin = end;
  }
  // Each take in each span, in output order, so that a cycle shown again is known as reused.
  for (int i = 0; i < n; ++i) {
    const PreparedTake& take = prepared.takes[static_cast<size_t>(i)];
    std::vector<bool> used(own_cycles(take).cycles.size(), false);
    const std::string name =
        static_cast<size_t>(i) < names.size() ? names[static_cast<size_t>(i)] : "take " + std::to_string(i + 1);
    for (CycleProvenance& span : spans) {
      TakeCycleSource s =
          source_in_span(take, fps, shown[static_cast<size_t>(i)], own[static_cast<size_t>(i)], span.begin, span.end);
      s.take = name;
      if (s.kind == CycleSourceKind::kCycle) {
        s.reused = used[static_cast<size_t>(s.cycle)];
        used[static_cast<size_t>(s.cycle)] = true;
      }
      span.takes.push_back(std::move(s));
    }
  }
  return spans;
}

int provenance_at(const std::vector<CycleProvenance>& spans, int frame) {
  const auto after = std::upper_bound(spans.begin(), spans.end(), frame,
                                      [](int f, const CycleProvenance& s) { return f < s.begin; });
  if (after == spans.begin()) return -1;
  const auto at = std::prev(after);
  return frame < at->end ? static_cast<int>(at - spans.begin()) : -1;
}

std::string provenance_text(const CycleProvenance& span, double fps) {
  if (!(fps > 0.0)) fps = 30.0;
  char line[256];
  if (span.cycle >= 0)
    std::snprintf(line, sizeof line, "Cycle %d of the result (%.2f-%.2f s)", span.cycle + 1, span.begin / fps,
                  span.end / fps);
  else
    std::snprintf(line, sizeof line, "Outside the reference's cycles (%.2f-%.2f s)", span.begin / fps, span.end / fps);
  std::string text = line;
  for (const TakeCycleSource& s : span.takes) {
    switch (s.kind) {
      case CycleSourceKind::kCycle:
        std::snprintf(line, sizeof line, "%s: cycle %d, frames %d-%d of its file (%.2f-%.2f s)%s", s.take.c_str(),
                      s.cycle + 1, s.first_frame, s.last_frame, s.begin_s, s.end_s, s.reused ? ", reused" : "");
        break;
      case CycleSourceKind::kOutsideCycles:
        std::snprintf(line, sizeof line, "%s: outside its cycles, frames %d-%d of its file (%.2f-%.2f s)",
                      s.take.c_str(), s.first_frame, s.last_frame, s.begin_s, s.end_s);
        break;
      case CycleSourceKind::kPostureOnly:
        std::snprintf(line, sizeof line, "%s: its posture only, on the reference's motion", s.take.c_str());
        break;
    }
    text += "\n";
    text += line;
  }
  return text;
}

}  // namespace mostyle::ui
