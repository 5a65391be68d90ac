#pragma once
// The look of a weight control while the weights are keyed over time (ui/model/keyed_weights.h),
// as animation tools tint a keyed field: its frame amber with a key at the playhead, green when
// the value shown is eased between keys; as usual without keys; and the words its tooltip adds.
// A tint lasts for the scope of one control:
//   { KeyedTint tint(keyed_at_playhead(state, takes)); range_slider(...); }
#include <imgui.h>

#include "ui/model/keyed_weights.h"
#include "ui/panels/theme.h"

namespace mostyle::ui {

// The sentence a weight control's tooltip adds while keyed ("" without keys).
inline const char* keyed_hint(Keyed keyed) {
  return keyed == Keyed::kNo ? ""
                             : "\nKeyed over time (the marks on the timeline): the value at this frame; moving it "
                               "sets the key here, or adds one.";
}

class KeyedTint {
 public:
  explicit KeyedTint(Keyed keyed) : pushed_(keyed != Keyed::kNo) {
    if (!pushed_) return;
    const ImVec4 frame = keyed == Keyed::kOnKey ? kOnKeyFrameColor : kKeyedFrameColor;
    const ImVec4 lighter(frame.x + 0.05f, frame.y + 0.05f, frame.z + 0.05f, frame.w);
    ImGui::PushStyleColor(ImGuiCol_FrameBg, frame);
    ImGui::PushStyleColor(ImGuiCol_FrameBgHovered, lighter);
    ImGui::PushStyleColor(ImGuiCol_FrameBgActive, lighter);
  }
  ~KeyedTint() {
    if (pushed_) ImGui::PopStyleColor(3);
  }
  KeyedTint(const KeyedTint&) = delete;
  KeyedTint& operator=(const KeyedTint&) = delete;

 private:
  bool pushed_;
};

}  // namespace mostyle::ui
