#pragma once
// What the editor's panels read and change, in one place. The app owns one EditorState and
// hands it to every panel each frame; panels never own engine data of their own. Plain data:
// no GL, no ImGui, so a test can build one by hand.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <glm/glm.hpp>

#include "engine/io/clip.h"

namespace mostyle::ui {

// The blend the animator asks for (DESIGN.md "The editor"; defaults from the paper's figures).
struct BlendParameters {
  double alpha = 0.5;     // 0: take A, 1: take B
  int components = 10;    // k
  double sparsity = 0.1;  // f in (0, 1]: fraction of non-zeros kept per component
};

// One loaded (or failed) BVH take.
struct Take {
  std::string path;
  std::string label;                      // file name without folder and extension
  std::string error;                      // non-empty: loading failed, shown as it is
  std::vector<std::string> warnings;      // recoverable defects the reader reported
  std::shared_ptr<const Clip> clip;       // null when error is set
  Eigen::MatrixXd positions;              // frames x 3*joints, world units (placed, see below)
  std::vector<int> parents;               // per joint, -1 for roots
  std::vector<std::uint8_t> hidden;       // per joint, nonzero: not drawn (a static rig ROOT)
  float size = 1.0f;                      // standing height, world units
  glm::vec3 color{0.8f};                  // sRGB, its skeleton and label
  bool visible = true;
  double fps = 0.0;                       // rate of `positions`; 0: the clip's own
  // Optional, frames x joints: 1 where the joint is planted (the engine's foot contacts);
  // empty: the viewport estimates contacts from the height above the floor.
  Eigen::MatrixXd contacts;
  // Optional, one per joint: rgb highlight (sRGB), a = strength (a component's joints).
  std::vector<glm::vec4> highlights;

  bool ok() const { return error.empty() && clip != nullptr; }
  int frames() const { return static_cast<int>(positions.rows()); }
  double rate() const { return fps > 0.0 ? fps : clip ? clip->fps() : 30.0; }
};

struct Playback {
  double time_s = 0.0;   // playhead, seconds from the first frame
  bool playing = true;
  float speed = 1.0f;    // playback rate, 1 = real time
  bool loop = true;
};

struct ViewOptions {
  bool follow = true;     // the camera follows the skeletons as they walk
  bool labels = true;
  bool grid = true;
  bool shadows = true;
  bool contacts = true;
  bool overlay = false;   // the takes drawn on top of each other instead of side by side
  int samples = 0;        // viewport MSAA samples; 0: automatic (4 on a GPU, 1 on llvmpipe)
  bool request_reframe = false;  // set by a panel: frame the skeletons on the next frame
};

struct EditorState {
  BlendParameters parameters;
  Playback playback;
  ViewOptions view;
  std::vector<Take> takes;

  // The take that sets the timeline (frame numbers, fps, length): the first that loaded.
  const Take* reference_take() const {
    for (const Take& t : takes)
      if (t.ok()) return &t;
    return nullptr;
  }
};

// Frame of `take` at time t (seconds), clamped to its range; 0 for a take without frames.
inline int frame_at(const Take& take, double time_s) {
  if (!take.ok() || take.frames() == 0) return 0;
  double f = time_s * take.rate();
  int frame = f <= 0.0 ? 0 : static_cast<int>(f + 1e-6);
  return frame >= take.frames() ? take.frames() - 1 : frame;
}

}  // namespace mostyle::ui
