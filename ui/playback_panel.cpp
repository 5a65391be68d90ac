#include "ui/playback_panel.h"

#include <algorithm>

#include <imgui.h>

namespace mostyle::ui {
namespace {
const ImVec4 kDimColor(0.60f, 0.62f, 0.66f, 1.0f);
constexpr float kMargin = 12.0f;
}  // namespace

void PlaybackPanel::draw(EditorState& state) {
  const ImGuiIO& io = ImGui::GetIO();
  const float height = ImGui::GetFrameHeight() + 2.0f * ImGui::GetStyle().WindowPadding.y;
  // Pinned to the bottom edge, full width: it follows the window when it is resized.
  ImGui::SetNextWindowPos(ImVec2(kMargin, io.DisplaySize.y - height - kMargin), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(io.DisplaySize.x - 2.0f * kMargin, height), ImGuiCond_Always);
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoMove |
                                 ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoSavedSettings;
  if (!ImGui::Begin("Playback", nullptr, flags)) {
    ImGui::End();
    return;
  }
  const Take* reference = state.reference_take();
  Playback& p = state.playback;
  if (reference == nullptr) {
    ImGui::TextColored(kDimColor, "No take loaded.");
    ImGui::End();
    return;
  }
  const double fps = reference->rate();
  const int last = std::max(reference->frames() - 1, 0);
  int frame = frame_at(*reference, p.time_s);

  // Keys, unless a text field has them: space plays and pauses, left/right step one frame.
  if (!io.WantTextInput) {
    if (ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Space), false)) p.playing = !p.playing;
    const bool back = ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_LeftArrow));
    const bool forward = ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_RightArrow));
    if (back || forward) {
      p.playing = false;
      frame = std::clamp(frame + (forward ? 1 : -1), 0, last);
      p.time_s = (frame + 0.5) / fps;
    }
  }
  if (ImGui::Button(p.playing ? "Pause" : "Play", ImVec2(64.0f, 0.0f))) p.playing = !p.playing;
  ImGui::SameLine();
  if (ImGui::Button("|<")) p.time_s = 0.0;
  ImGui::SameLine();
  ImGui::SetNextItemWidth(120.0f);
  ImGui::SliderFloat("##speed", &p.speed, 0.1f, 2.0f, "speed %.2fx");
  ImGui::SameLine();
  ImGui::Checkbox("loop", &p.loop);
  ImGui::SameLine();
  ImGui::TextColored(kDimColor, "%6.2f s   %.0f fps", frame / fps, fps);
  ImGui::SameLine();
  ImGui::SetNextItemWidth(-1.0f);
  if (ImGui::SliderInt("##frame", &frame, 0, last, "frame %d")) p.time_s = (frame + 0.5) / fps;
  ImGui::End();
}

}  // namespace mostyle::ui
