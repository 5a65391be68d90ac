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

// "weights 0.20, 0.30, 0.50": a key's weights, one per take.
std::string weights_words(const std::vector<double>& w) {
  char number[32];
  std::string words = "weights ";
  for (std::size_t i = 0; i < w.size(); ++i) {
    std::snprintf(number, sizeof number, "%s%.2f", i == 0 ? "" : ", ", w[i]);
    words += number;
  }
  return words;
}

// What the timeline shows of the reference take: its rate, length and last frame, and the
// number of takes mixed (the weights a key holds).
struct Timeline {
  const ShownMotion* reference = nullptr;
  double fps = 0.0;
  double length_s = 0.0;
  int last = 0;
  int takes = 0;
};

// Where the frame slider sits, pixels.
struct SliderPlace {
  ImVec2 at;  // its top left corner
  float w = 0.0f, h = 0.0f;
  Track track;
  float mark_y = 0.0f;  // the keys' diamonds' centres: along the slider's top edge
};

// The window, pinned to the bottom edge, full width: it follows the window when it is resized.
// false: collapsed (ended already).
bool begin_window() {
  const PanelRect r = panel_rect(PanelId::kPlayback);
  ImGui::SetNextWindowPos(ImVec2(r.x, r.y), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(r.w, r.h), ImGuiCond_Always);
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoMove |
                                 ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoSavedSettings;
  if (!ImGui::Begin(panel_title(PanelId::kPlayback), nullptr, flags)) {
    ImGui::End();
    return false;
  }
  return true;
}

// Keys, unless ImGui has them (a text field, a slider held): space plays and pauses,
// left/right step one frame, K keys the weights here (Delete: with the marks).
void handle_keys(EditorState& state, const Timeline& t, int* frame) {
  const ImGuiIO& io = ImGui::GetIO();
  Playback& p = state.playback;
  if (ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Space), false)) toggle_playback(p, t.length_s);
  const bool back = ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_LeftArrow));
  const bool forward = ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_RightArrow));
  if (back || forward) {
    p.playing = false;
    *frame = std::clamp(*frame + (forward ? 1 : -1), 0, t.last);
    p.time_s = (*frame + 0.5) / t.fps;
  }
  bool key = false;
  for (ImWchar c : io.InputQueueCharacters) key |= c == 'k' || c == 'K';  // any keyboard layout
  if (key && !io.KeyCtrl && !io.KeyAlt && !io.KeySuper) key_at_playhead(state, t.takes);
}

// Play/pause, rewind, speed, loop, the time and rate, Set key; each followed by SameLine.
void draw_transport(EditorState& state, const Timeline& t, int frame) {
  Playback& p = state.playback;
  const double fps = t.fps;
  if (ImGui::Button(p.playing ? "Pause" : "Play", ImVec2(64.0f, 0.0f))) toggle_playback(p, t.length_s);
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
  if (ImGui::Button("Set key")) key_at_playhead(state, t.takes);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Key the style at this frame (K): the takes' weights, as the weights show them now (a key "
                      "already here takes them).\nThe style eases from key to key over the result; with keys, moving a "
                      "weight keys it at the playhead.\nOn the timeline: drag a key to move it, click it to go to it, "
                      "right-click it (or Delete) to remove it.");
  ImGui::SameLine();
}

// The keys' marks as items over the slider's top edge: drag one to move its key in time, click
// it to go there, right-click it to remove it. Returns the key under the mouse (or held), -1:
// none; *removed: the key right-clicked, else left as it was.
int key_mark_items(EditorState& state, const Timeline& t, const SliderPlace& slider, bool* mark_dragged,
                   int* removed) {
  const ImGuiIO& io = ImGui::GetIO();
  Playback& p = state.playback;
  WeightKeys& keys = state.document.controls.keys;
  const double fps = t.fps;
  int hovered = -1;
  for (int i = 0; i < static_cast<int>(keys.size()); ++i) {
    WeightKey& key = keys[static_cast<size_t>(i)];
    ImGui::PushID(i);
    ImGui::SetCursorScreenPos(ImVec2(slider.track.x(key.seconds * fps) - kMarkHit, slider.at.y));
    const bool released = ImGui::InvisibleButton(
        "##key", ImVec2(2.0f * kMarkHit, 0.5f * slider.h), ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight);
    if (ImGui::IsItemActivated()) *mark_dragged = false;
    if (ImGui::IsItemActive() && ImGui::IsMouseDragging(ImGuiMouseButton_Left)) {
      // Dragged: to the frame under the mouse, between its neighbours (one undo step when let go).
      const double to = slider.track.frame(io.MousePos.x) / fps;
      if (to != key.seconds) move_key(keys, i, to, 1.0 / fps, t.length_s);
      *mark_dragged = true;
    }
    const int key_frame = static_cast<int>(std::lround(key.seconds * fps));
    if (released && ImGui::IsMouseReleased(ImGuiMouseButton_Right)) {
      *removed = i;
    } else if (released && !*mark_dragged) {  // a click: the playhead to the key, to edit it
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
  ImGui::SetCursorScreenPos(slider.at);
  return hovered;
}

// The frame slider, and its tooltip when hovered (not over a key's mark, `hovered_key`): the
// output cycle under the mouse and where each take's part of it came from, then how to use
// the slider. Returns that cycle's span of state.cycle_provenance; -1: none.
int draw_frame_slider(EditorState& state, const Timeline& t, const SliderPlace& slider, int frame, int hovered_key) {
  const ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextItemWidth(slider.w);
  if (ImGui::SliderInt("##frame", &frame, 0, t.last, "frame %d")) state.playback.time_s = (frame + 0.5) / t.fps;
  // IsItemHovered does not ask whether an item submitted before took the mouse, and a later
  // tooltip replaces an earlier one: hence not over a key's mark.
  int span = -1;
  if (ImGui::IsItemHovered() && hovered_key < 0) {
    static const char* kSliderHelp =
        "Drag to go to a frame; left and right arrow keys step one frame.\nTicks: where the "
        "reference's cycles (gait cycles, periods) begin. Diamonds: keys of the style (Set key, K)";
    span = provenance_at(state.cycle_provenance, slider.track.frame(io.MousePos.x));
    if (span >= 0) {
      ImGui::BeginTooltip();
      ImGui::TextUnformatted(provenance_text(state.cycle_provenance[static_cast<size_t>(span)], t.fps).c_str());
      ImGui::Separator();
      ImGui::TextDisabled("%s", kSliderHelp);
      ImGui::EndTooltip();
    } else {
      ImGui::SetTooltip("%s", kSliderHelp);
    }
  }
  return span;
}

// Drawn over the slider: the span the tooltip speaks of, the reference's cycle starts, the keys.
void draw_slider_marks(const EditorState& state, const Timeline& t, const SliderPlace& slider, int span,
                       int hovered_key) {
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const Track& track = slider.track;
  // The span the tooltip speaks of, underlined along the slider's bottom edge.
  if (span >= 0 && t.last > 0) {
    const CycleProvenance& under = state.cycle_provenance[static_cast<size_t>(span)];
    const float bottom = slider.at.y + slider.h - 1.0f;
    dl->AddLine(ImVec2(track.x(under.begin), bottom), ImVec2(track.x(under.end), bottom),
                ImGui::GetColorU32(ImGuiCol_SliderGrabActive), 2.0f);
  }
  // A tick where each of the reference's cycles begins, along the slider's bottom edge.
  if (t.last > 0) {
    const float bottom = slider.at.y + slider.h;
    for (int f : t.reference->cycle_starts) {
      const float x = track.x(f);
      dl->AddLine(ImVec2(x, bottom - 6.0f), ImVec2(x, bottom - 1.0f), ImGui::GetColorU32(ImGuiCol_TextDisabled), 1.5f);
    }
  }
  // A diamond at each key, along the top edge: brighter under the mouse and at the playhead.
  const WeightKeys& keys = state.document.controls.keys;
  if (keys_fit(keys, t.takes)) {
    const KeyTime at = key_time(state);
    const int on_key = key_near(keys, at.seconds, at.tolerance_s);
    const float mark_y = slider.mark_y;
    for (int i = 0; i < static_cast<int>(keys.size()); ++i) {
      const float x = track.x(keys[static_cast<size_t>(i)].seconds * t.fps);
      const float h = i == hovered_key ? kMarkHalf + 1.5f : kMarkHalf;
      const ImVec2 corners[4] = {{x, mark_y - h}, {x + h, mark_y}, {x, mark_y + h}, {x - h, mark_y}};
      dl->AddConvexPolyFilled(corners, 4, ImGui::GetColorU32(kKeyColor));
      const bool lit = i == hovered_key || i == on_key;
      dl->AddPolyline(corners, 4, lit ? IM_COL32(255, 255, 255, 235) : IM_COL32(20, 20, 20, 220), ImDrawFlags_Closed,
                      lit ? 1.5f : 1.0f);
    }
  }
}

}  // namespace

void PlaybackPanel::draw(EditorState& state) {
  const ImGuiIO& io = ImGui::GetIO();
  hovered_span_ = -1;
  if (!begin_window()) return;
  // The list of keys, reachable from here without knowing its key.
  if (ImGui::Button("Shortcuts")) command_toggle_shortcuts(state);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Every key and mouse gesture, Frame all and Reset layout (F1 or ?)");
  ImGui::SameLine();
  const ShownMotion* reference = state.reference_take();
  if (reference == nullptr) {
    ImGui::TextColored(kDimColor, "No take loaded.");
    ImGui::End();
    return;
  }
  Timeline t;
  t.reference = reference;
  t.fps = reference->rate();
  t.length_s = take_length_s(*reference);
  t.last = std::max(reference->frames() - 1, 0);
  t.takes = static_cast<int>(state.document.files.size());  // the takes mixed: two for a pair
  int frame = frame_at(*reference, state.playback.time_s);
  WeightKeys& keys = state.document.controls.keys;
  const bool keyed = keys_fit(keys, t.takes);

  const bool keyboard = !io.WantTextInput && !io.WantCaptureKeyboard;
  if (keyboard) handle_keys(state, t, &frame);
  draw_transport(state, t, frame);

  // The frame slider with its marks. The keys' marks are items submitted before the slider, so
  // that a press on a mark is the mark's (ImGui gives the mouse to the item submitted first); they
  // are drawn after it, over its frame.
  SliderPlace slider;
  slider.at = ImGui::GetCursorScreenPos();
  slider.w = ImGui::GetContentRegionAvail().x;
  slider.h = ImGui::GetFrameHeight();
  slider.track = track_of(slider.at.x, slider.w, t.last);
  slider.mark_y = slider.at.y + kMarkHalf + 1.0f;
  int hovered = -1, removed = -1;
  if (keyed) hovered = key_mark_items(state, t, slider, &mark_dragged_, &removed);
  if (keyboard && keyed && ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Delete), false)) {
    const KeyTime at = key_time(state);
    removed = hovered >= 0 ? hovered : key_near(keys, at.seconds, at.tolerance_s);
  }
  if (removed >= 0) {
    remove_key(state, t.takes, removed);
    hovered = -1;
  }
  const int span = draw_frame_slider(state, t, slider, frame, hovered);
  hovered_span_ = span;
  draw_slider_marks(state, t, slider, span, hovered);
  ImGui::End();
}

}  // namespace mostyle::ui
