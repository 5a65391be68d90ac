#include "ui/panels/structure_strip.h"

#include <algorithm>

#include "ui/model/take_structure.h"

namespace mostyle::ui {
namespace {

constexpr ImU32 kRestColor = IM_COL32(70, 74, 84, 255);
constexpr ImU32 kPostureColor = IM_COL32(30, 31, 36, 255);

ImU32 faded(ImU32 color, float alpha) {
  ImVec4 c = ImGui::ColorConvertU32ToFloat4(color);
  c.w = alpha;
  return ImGui::ColorConvertFloat4ToU32(c);
}

}  // namespace

void draw_structure_strip(const PreparedTake& take, ImVec2 min, ImVec2 max, int frames, bool down, ImU32 color,
                          const std::function<double(int)>& own_frame_at) {
  if (frames < 1) return;
  ImDrawList* dl = ImGui::GetWindowDrawList();
  // Along the strip: frame f's edge; across it: an inset from either side.
  const float along0 = down ? min.y : min.x, along1 = down ? max.y : max.x;
  const float across0 = down ? min.x : min.y, across1 = down ? max.x : max.y;
  auto at = [&](double f) { return along0 + static_cast<float>(f / frames) * (along1 - along0); };
  auto rect = [&](double f0, double f1, float inset, ImU32 c) {
    const float a0 = at(f0), a1 = at(f1), b0 = across0 + inset, b1 = across1 - inset;
    if (down) dl->AddRectFilled(ImVec2(b0, a0), ImVec2(b1, a1), c);
    else dl->AddRectFilled(ImVec2(a0, b0), ImVec2(a1, b1), c);
  };
  auto tick = [&](double f) {
    const float a = at(f);
    if (down) dl->AddLine(ImVec2(across0, a), ImVec2(across1, a), color, 1.5f);
    else dl->AddLine(ImVec2(a, across0), ImVec2(a, across1), color, 1.5f);
  };
  const float band_inset = 0.25f * (across1 - across0);
  for (const StructureSpan& run : structure_spans(take, frames, own_frame_at)) {
    switch (run.structure.part) {
      case FramePart::kPosture: rect(run.begin, run.end, 0.0f, kPostureColor); break;
      case FramePart::kRest: rect(run.begin, run.end, 0.0f, kRestColor); break;
      case FramePart::kAction: rect(run.begin, run.end, 0.0f, faded(color, 0.28f)); break;
      case FramePart::kCycle:
        rect(run.begin, run.end, 0.0f, faded(color, 0.28f));
        rect(run.begin, run.end, band_inset, faded(color, run.structure.index % 2 == 0 ? 0.55f : 0.38f));
        tick(run.begin);
        break;
    }
  }
}

}  // namespace mostyle::ui
