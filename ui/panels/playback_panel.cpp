#include "ui/panels/playback_panel.h"
#include "ui/panels/theme.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <string>
#include <vector>

#include <imgui.h>

#include "ui/model/keyed_weights.h"
#include "ui/model/weight_keys_edit.h"
#include "ui/panels/layout.h"

namespace mostyle::ui {
namespace {

constexpr float kMarkHalf = 5.0f;  // a key's diamond: half its width and height, pixels
constexpr float kMarkHit = 7.0f;   // half the width of the area that picks a key's mark, pixels

// The frame slider's track: where ImGui's SliderInt puts its grab's centre at each frame 0..last
// (inside its padding and half a grab from either end), pixels.
struct Track {
  float x0 = 0.0f, x1 = 0.0f;  // at frame 0 and at frame `last`
  int last = 0;
  float x(double frame) const {
    return last > 0 ? x0 + (x1 - x0) * static_cast<float>(std::clamp(frame / last, 0.0, 1.0)) : x0;
  }
  int frame(float px) const {
    return last > 0 && x1 > x0 ? std::clamp(static_cast<int>(std::lround((px - x0) / (x1 - x0) * last)), 0, last) : 0;
  }
};

Track track_of(float left, float width, int last) {
  const float inset = 2.0f + 0.5f * ImGui::GetStyle().GrabMinSize;  // ImGui's grab padding and half grab
  return Track{left + inset, left + width - inset, last};
}

// "alpha 0.30" for a pair, "weights 0.20, 0.30, 0.50" for a palette.
std::string weights_words(const std::vector<double>& w) {
  char number[32];
  if (w.size() == 2) {
    std::snprintf(number, sizeof number, "alpha %.2f", w[1]);
    return number;
  }
  std::string words = "weights ";
  for (std::size_t i = 0; i < w.size(); ++i) {
    std::snprintf(number, sizeof number, "%s%.2f", i == 0 ? "" : ", ", w[i]);
    words += number;
  }
  return words;
}

}  // namespace

void PlaybackPanel::draw(EditorState& state) {
  const ImGuiIO& io = ImGui::GetIO();
  hovered_span_ = -1;
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
  // The takes mixed (two for a pair): the number of weights a key holds.
  const int takes = static_cast<int>(state.document.files.size());
  WeightKeys& keys = state.document.controls.keys;
  const bool keyed = keys_fit(keys, takes);

  // Keys, unless ImGui has them (a text field, a slider held): space plays and pauses,
  // left/right step one frame, K keys the weights here (Delete: below, over the marks).
  const bool keyboard = !io.WantTextInput && !io.WantCaptureKeyboard;
  if (keyboard) {
    if (ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Space), false)) toggle_playback(p, length_s);
    const bool back = ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_LeftArrow));
    const bool forward = ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_RightArrow));
    if (back || forward) {
      p.playing = false;
      frame = std::clamp(frame + (forward ? 1 : -1), 0, last);
      p.time_s = (frame + 0.5) / fps;
    }
    bool key = false;
    for (ImWchar c : io.InputQueueCharacters) key |= c == 'k' || c == 'K';  // any keyboard layout
    if (key && !io.KeyCtrl && !io.KeyAlt && !io.KeySuper) key_at_playhead(state, takes);
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
  if (ImGui::Button("Set key")) key_at_playhead(state, takes);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Key the style at this frame (K): %s, as the sliders show it now (a key already here takes "
                      "it).\nThe style eases from key to key over the result; with keys, moving a weight keys it at "
                      "the playhead.\nOn the timeline: drag a key to move it, click it to go to it, right-click it "
                      "(or Delete) to remove it.",
                      takes == 2 ? "alpha" : "the palette's weights");
  ImGui::SameLine();

  // The frame slider with its marks. The keys' marks are items submitted before the slider, so
  // that a press on a mark is the mark's (ImGui gives the mouse to the item submitted first); they
  // are drawn after it, over its frame.
  const ImVec2 slider_at = ImGui::GetCursorScreenPos();
  const float slider_w = ImGui::GetContentRegionAvail().x;
  const float slider_h = ImGui::GetFrameHeight();
  const Track track = track_of(slider_at.x, slider_w, last);
  const float mark_y = slider_at.y + kMarkHalf + 1.0f;  // along the slider's top edge
  int hovered = -1, removed = -1;
  if (keyed) {
    for (int i = 0; i < static_cast<int>(keys.size()); ++i) {
      WeightKey& key = keys[static_cast<size_t>(i)];
      ImGui::PushID(i);
      ImGui::SetCursorScreenPos(ImVec2(track.x(key.seconds * fps) - kMarkHit, slider_at.y));
      const bool released = ImGui::InvisibleButton(
          "##key", ImVec2(2.0f * kMarkHit, 0.5f * slider_h), ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight);
      if (ImGui::IsItemActivated()) mark_dragged_ = false;
      if (ImGui::IsItemActive() && ImGui::IsMouseDragging(ImGuiMouseButton_Left)) {
        // Dragged: to the frame under the mouse, between its neighbours (one undo step when let go).
        const double to = track.frame(io.MousePos.x) / fps;
        if (to != key.seconds) move_key(keys, i, to, 1.0 / fps, length_s);
        mark_dragged_ = true;
      }
      const int key_frame = static_cast<int>(std::lround(key.seconds * fps));
      if (released && ImGui::IsMouseReleased(ImGuiMouseButton_Right)) {
        removed = i;
      } else if (released && !mark_dragged_) {  // a click: the playhead to the key, to edit it
        p.playing = false;
        p.time_s = (key_frame + 0.5) / fps;
      }
      if (ImGui::IsItemHovered() || ImGui::IsItemActive()) {
        hovered = i;
        ImGui::SetTooltip("Key %d at %.2f s (frame %d): %s\nDrag to move it in time, click to go to it, right-click "
                          "or Delete to remove it",
                          i + 1, key.seconds, key_frame, weights_words(key.weights).c_str());
      }
      ImGui::PopID();
    }
    ImGui::SetCursorScreenPos(slider_at);
  }
  if (keyboard && keyed && ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Delete), false)) {
    const KeyTime at = key_time(state);
    removed = hovered >= 0 ? hovered : key_near(keys, at.seconds, at.tolerance_s);
  }
  if (removed >= 0) {
    remove_key(state, takes, removed);
    hovered = -1;
  }

  ImGui::SetNextItemWidth(slider_w);
  if (ImGui::SliderInt("##frame", &frame, 0, last, "frame %d")) p.time_s = (frame + 0.5) / fps;
  // Hovered: the output cycle under the mouse and where each take's part of it came from, then
  // how to use the slider. Not over a key's mark: IsItemHovered does not ask whether an item
  // submitted before took the mouse, and a later tooltip replaces an earlier one.
  int span = -1;
  if (ImGui::IsItemHovered() && hovered < 0) {
    static const char* kSliderHelp =
        "Drag to go to a frame; left and right arrow keys step one frame.\nTicks: where the "
        "reference's cycles (gait cycles, periods) begin. Diamonds: keys of the style (Set key, K)";
    span = provenance_at(state.cycle_provenance, track.frame(io.MousePos.x));
    if (span >= 0) {
      ImGui::BeginTooltip();
      ImGui::TextUnformatted(provenance_text(state.cycle_provenance[static_cast<size_t>(span)], fps).c_str());
      ImGui::Separator();
      ImGui::TextDisabled("%s", kSliderHelp);
      ImGui::EndTooltip();
    } else {
      ImGui::SetTooltip("%s", kSliderHelp);
    }
  }
  hovered_span_ = span;
  ImDrawList* dl = ImGui::GetWindowDrawList();
  // The span the tooltip speaks of, underlined along the slider's bottom edge.
  if (span >= 0 && last > 0) {
    const CycleProvenance& under = state.cycle_provenance[static_cast<size_t>(span)];
    const float bottom = slider_at.y + slider_h - 1.0f;
    dl->AddLine(ImVec2(track.x(under.begin), bottom), ImVec2(track.x(under.end), bottom),
                ImGui::GetColorU32(ImGuiCol_SliderGrabActive), 2.0f);
  }
  // A tick where each of the reference's cycles begins, along the slider's bottom edge.
  if (last > 0) {
    const float bottom = slider_at.y + slider_h;
    for (int f : reference->cycle_starts) {
      const float x = track.x(f);
      dl->AddLine(ImVec2(x, bottom - 6.0f), ImVec2(x, bottom - 1.0f), ImGui::GetColorU32(ImGuiCol_TextDisabled), 1.5f);
    }
  }
  // A diamond at each key, along the top edge: brighter under the mouse and at the playhead.
  if (keys_fit(keys, takes)) {
    const KeyTime at = key_time(state);
    const int on_key = key_near(keys, at.seconds, at.tolerance_s);
    for (int i = 0; i < static_cast<int>(keys.size()); ++i) {
      const float x = track.x(keys[static_cast<size_t>(i)].seconds * fps);
      const float h = i == hovered ? kMarkHalf + 1.5f : kMarkHalf;
      const ImVec2 corners[4] = {{x, mark_y - h}, {x + h, mark_y}, {x, mark_y + h}, {x - h, mark_y}};
      dl->AddConvexPolyFilled(corners, 4, ImGui::GetColorU32(kKeyColor));
      const bool lit = i == hovered || i == on_key;
      dl->AddPolyline(corners, 4, lit ? IM_COL32(255, 255, 255, 235) : IM_COL32(20, 20, 20, 220), ImDrawFlags_Closed,
                      lit ? 1.5f : 1.0f);
    }
  }
  ImGui::End();
}

}  // namespace mostyle::ui
