#pragma once
// The 3D viewport's ImGui side: mouse navigation of the camera and text over the scene.
// The viewport fills the window behind every panel; ImGui's display size is its size.
#include <vector>

#include "render/camera.h"
#include "render/skeleton_pose.h"

namespace mostyle::ui {

// Orbit (left drag), pan (right or middle drag), zoom (wheel) from ImGui's mouse state, only
// when ImGui does not want the mouse (no panel under it or being dragged). Call between
// ImGui::NewFrame() and ImGui::Render(). Returns true when the camera moved.
bool apply_camera_input(render::OrbitCamera& camera);

// Each visible skeleton's label above its head, in its colour, on the background draw list
// (under every panel). Uses the camera as the viewport was drawn with it.
void draw_skeleton_labels(const std::vector<render::SkeletonPose>& poses, const render::OrbitCamera& camera);

// A line of text at the top right of the viewport, left of the right column (frame time, hints).
void draw_viewport_status(const char* text);

}  // namespace mostyle::ui
