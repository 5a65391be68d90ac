#include "ui/panels/viewport_overlay.h"

#include <vector>

#include <imgui.h>

#include "ui/panels/layout.h"

namespace mostyle::ui {
namespace {
ImU32 to_imgui_color(const glm::vec3& c, float alpha = 1.0f) {
  return ImGui::ColorConvertFloat4ToU32(ImVec4(c.r, c.g, c.b, alpha));
}
}  // namespace

bool apply_camera_input(render::OrbitCamera& camera) {
  ImGuiIO& io = ImGui::GetIO();
  if (io.WantCaptureMouse) return false;
  bool moved = false;
  const float dx = io.MouseDelta.x, dy = io.MouseDelta.y;
  const bool dragged = dx != 0.0f || dy != 0.0f;
  if (ImGui::IsMouseDown(ImGuiMouseButton_Left) && dragged) {
    camera.orbit(dx, dy);
    moved = true;
  } else if ((ImGui::IsMouseDown(ImGuiMouseButton_Right) || ImGui::IsMouseDown(ImGuiMouseButton_Middle)) && dragged) {
    camera.pan(dx, dy, io.DisplaySize.y);
    moved = true;
  }
  if (io.MouseWheel != 0.0f) {
    camera.zoom(io.MouseWheel);
    moved = true;
  }
  return moved;
}

constexpr int kMaxStackedLabels = 3;  // labels stacked over one spot, at most

void draw_skeleton_labels(const std::vector<render::SkeletonPose>& poses, const render::OrbitCamera& camera) {
  ImGuiIO& io = ImGui::GetIO();
  const glm::ivec2 viewport(static_cast<int>(io.DisplaySize.x), static_cast<int>(io.DisplaySize.y));
  if (viewport.x <= 0 || viewport.y <= 0) return;
  const glm::mat4 view_projection =
      camera.view_projection(io.DisplaySize.x / io.DisplaySize.y);
  ImDrawList* draw = ImGui::GetBackgroundDrawList();
  std::vector<ImVec4> placed;  // label boxes so far (x0, y0, x1, y1): later ones step up
  // The reference and the result (the first and the last skeleton) are labelled before the
  // other takes, so that they keep their labels where some are left out.
  std::vector<size_t> order;
  if (!poses.empty()) order = {0, poses.size() - 1};
  for (size_t i = 1; i + 1 < poses.size(); ++i) order.push_back(i);
  if (poses.size() == 1) order.pop_back();
  for (size_t index : order) {
    const render::SkeletonPose& pose = poses[index];
    if (pose.label.empty() || pose.positions.empty()) continue;
    render::ScreenPoint p = render::project_to_pixels(view_projection, render::label_anchor(pose), viewport);
    if (!p.visible) continue;
    const char* text = pose.label.c_str();
    ImVec2 extent = ImGui::CalcTextSize(text);
    ImVec2 at(p.pixel.x - 0.5f * extent.x, p.pixel.y - extent.y);
    const float pad = 4.0f;
    ImVec4 box(at.x - pad - 8.0f, at.y - 2.0f, at.x + extent.x + pad, at.y + extent.y + 2.0f);
    int steps = 0;  // labels this one was moved above
    for (bool moved = true; moved;) {
      moved = false;
      for (const ImVec4& other : placed) {
        if (box.x < other.z && other.x < box.z && box.y < other.w && other.y < box.w) {
          const float up = box.w - other.y + 3.0f;
          box.y -= up;
          box.w -= up;
          at.y -= up;
          moved = true;
          ++steps;
        }
      }
    }
    // Skeletons on one spot (overlaid, a palette's ghosts) would pile their labels into a column
    // far above them: past a few, a label is left out (the takes panel names every colour).
    if (steps >= kMaxStackedLabels) continue;
    placed.push_back(box);
    draw->AddRectFilled(ImVec2(box.x, box.y), ImVec2(box.z, box.w), IM_COL32(16, 17, 19, 170), 4.0f);
    draw->AddCircleFilled(ImVec2(at.x - 5.0f, at.y + 0.5f * extent.y), 3.5f, to_imgui_color(pose.color));
    draw->AddText(ImVec2(at.x + 1.0f, at.y), to_imgui_color(glm::mix(pose.color, glm::vec3(1.0f), 0.35f)), text);
  }
}

void draw_viewport_status(const char* text) {
  // Left of the right column (the layout's), where no panel covers it.
  ImVec2 extent = ImGui::CalcTextSize(text);
  ImVec2 at(panel_rect(PanelId::kComponents).x - extent.x - kLayoutMargin, 10.0f);
  ImGui::GetBackgroundDrawList()->AddText(at, IM_COL32(150, 154, 162, 255), text);
}

}  // namespace mostyle::ui
