#include "ui/panels/playback_panel.h"
#include "ui/panels/theme.h"

#include <algorithm>

#include <imgui.h>

#include "ui/panels/layout.h"

namespace mostyle::ui {
namespace {
}  // namespace

void PlaybackPanel::draw(EditorState& state) {
  const ImGuiIO& io = ImGui::GetIO();
  // Pinned to the bottom edge, full width: it follows the window when it is resized.
  const PanelRect r = panel_rect(PanelId::kPlayback);
  ImGui::SetNextWindowPos(ImVec2(r.x, r.y), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(r.w, r.h), ImGuiCond_Always);
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoMove |
                                 ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoSavedSettings;
  if (!ImGui::Begin(panel_title(PanelId::kPlayback), nullptr, flags)) {
    ImGui::End();
    return;
  }
  // The list of keys, reachable from here without knowing its key.
  if (ImGui::Button("Keys")) command_toggle_keys(state);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Every key and mouse gesture, Frame all and Reset layout (F1 or ?)");
  ImGui::SameLine();
  const Take* reference = state.reference_take();
  Playback& p = state.playback;
  if (reference == nullptr) {
    ImGui::TextColored(kDimColor, "No take loaded.");
    ImGui::End();
    return;
  }
  const double fps = reference->rate();
  const double length_s = take_length_s(*reference);
  const int last = std::max(reference->frames() - 1, 0);
  int frame = frame_at(*reference, p.time_s);

  // Keys, unless ImGui has them (a text field, a slider held): space plays and pauses,
  // left/right step one frame.
  if (!io.WantTextInput && !io.WantCaptureKeyboard) {
    if (ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Space), false)) toggle_playback(p, length_s);
    const bool back = ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_LeftArrow));
    const bool forward = ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_RightArrow));
    if (back || forward) {
      p.playing = false;
      frame = std::clamp(frame + (forward ? 1 : -1), 0, last);
      p.time_s = (frame + 0.5) / fps;
    }
  }
  if (ImGui::Button(p.playing ? "Pause" : "Play", ImVec2(64.0f, 0.0f))) toggle_playback(p, length_s);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(p.playing ? "Pause (space)" : "Play (space); from the start when on the last frame");
  ImGui::SameLine();
  if (ImGui::Button("|<")) p.time_s = 0.0;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Back to the first frame");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(120.0f);
  ImGui::SliderFloat("##speed", &p.speed, 0.1f, 2.0f, "speed %.2fx");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Playback speed: 1 is real time, 0.5 half as fast");
  ImGui::SameLine();
  ImGui::Checkbox("loop", &p.loop);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("On: start again after the last frame. Off: stop there.");
  ImGui::SameLine();
  ImGui::TextColored(kDimColor, "%6.2f s   %.0f fps", frame / fps, fps);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Time of this frame, and the frames per second of the takes");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(-1.0f);
  if (ImGui::SliderInt("##frame", &frame, 0, last, "frame %d")) p.time_s = (frame + 0.5) / fps;
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Drag to go to a frame; left and right arrow keys step one frame.\nTicks: where the "
                      "reference's cycles (gait cycles, periods) begin");
  // A tick where each of the reference's cycles begins, along the slider's track.
  if (last > 0) {
    const ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
    const float inset = 2.0f + 0.5f * ImGui::GetStyle().GrabMinSize;  // ImGui's grab padding and half grab
    ImDrawList* dl = ImGui::GetWindowDrawList();
    for (int f : reference->cycle_starts) {
      const float x = lo.x + inset + (hi.x - lo.x - 2.0f * inset) * static_cast<float>(f) / static_cast<float>(last);
      dl->AddLine(ImVec2(x, hi.y - 6.0f), ImVec2(x, hi.y - 1.0f), ImGui::GetColorU32(ImGuiCol_TextDisabled), 1.5f);
    }
  }
  ImGui::End();
}

}  // namespace mostyle::ui
