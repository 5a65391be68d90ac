#include "ui/model/take_structure.h"

#include <algorithm>
#include <cmath>

namespace mostyle::ui {

FrameStructure frame_structure(const PreparedTake& take, double frame) {
  if (std::isnan(frame)) return {FramePart::kPosture, -1};
  const int f = static_cast<int>(std::floor(frame));
  const std::vector<Cycle>& cycles = take.cycles.cycles;
  for (size_t c = 0; c < cycles.size(); ++c)
    if (f >= cycles[c].begin && f < cycles[c].end) return {FramePart::kCycle, static_cast<int>(c)};
  const std::vector<FrameSpan>& actions = take.cycles.spans.actions;
  for (size_t a = 0; a < actions.size(); ++a)
    if (f >= actions[a].begin && f < actions[a].end) return {FramePart::kAction, static_cast<int>(a)};
  return {FramePart::kRest, -1};
}

double own_frame(const PreparedTake& take, int frame) {
  const Eigen::VectorXd& source = take.registration.source;
  if (take.registration.empty() || source.size() == 0) return frame;
  return source[std::clamp<Eigen::Index>(frame, 0, source.size() - 1)];
}

std::vector<StructureSpan> structure_spans(const PreparedTake& take, int frames,
                                           const std::function<double(int)>& own_frame_at) {
  std::vector<StructureSpan> out;
  double before = NAN;
  for (int f = 0; f < frames; ++f) {
    const double own = own_frame_at(f);
    const FrameStructure s = frame_structure(take, own);
    if (out.empty() || s != out.back().structure || own < before) out.push_back(StructureSpan{f, f, s});
    out.back().end = f + 1;
    before = own;
  }
  return out;
}

std::string frame_structure_words(const PreparedTake& take, double frame) {
  const FrameStructure s = frame_structure(take, frame);
  const ActionSpans& spans = take.cycles.spans;
  auto of = [](const char* what, int i, size_t n) { return std::string(what) + " " + std::to_string(i + 1) + " of " + std::to_string(n); };
  switch (s.part) {
    case FramePart::kPosture: return "its posture only";
    case FramePart::kCycle:
      return of(take.cycles.kind == CycleKind::kGait ? "gait cycle" : "stroke", s.index, take.cycles.cycles.size());
    case FramePart::kAction: return of("action", s.index, spans.actions.size());
    case FramePart::kRest: break;
  }
  const int f = static_cast<int>(std::floor(frame));
  if (spans.still()) return "at rest";
  if (f < spans.rest_before) return "at rest before the action";
  if (f >= spans.frames - spans.rest_after) return "at rest after the action";
  return "a pause between actions";
}

}  // namespace mostyle::ui
