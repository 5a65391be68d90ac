#pragma once
// A BlendSession with the bundled pair (or two takes given) loaded and decomposed (small k,
// quick), and every editor panel over it, in the order the editor draws them: for the model,
// panel and layout tests.
#include <memory>
#include <string>
#include <vector>

#include "tests/test_data.h"
#include "ui/model/blend_session.h"
#include "ui/panels/components_panel.h"
#include "ui/panels/layers_panel.h"
#include "ui/panels/files_panel.h"
#include "ui/panels/metrics_panel.h"
#include "ui/panels/parameters_panel.h"
#include "ui/panels/playback_panel.h"
#include "ui/panels/takes_panel.h"

namespace mostyle::test {

struct LoadedSession {
  ui::EditorState state;
  ui::BlendSession session;
  LoadedSession() : LoadedSession(asset("motions/cmu142_walk_happy.bvh"), asset("motions/cmu142_walk_marching.bvh")) {}
  LoadedSession(const std::string& a, const std::string& b) {
    state.document.parameters.components = 6;  // small and quick
    state.document.parameters.sparsity = 0.2;
    session.load(a, b);
    session.wait_idle(state);
  }
};

inline std::vector<std::unique_ptr<ui::Panel>> all_panels(ui::BlendSession& session) {
  std::vector<std::unique_ptr<ui::Panel>> panels;
  panels.push_back(std::make_unique<ui::TakesPanel>());
  panels.push_back(std::make_unique<ui::ParametersPanel>(session));
  panels.push_back(std::make_unique<ui::FilesPanel>(session, asset("motions")));
  panels.push_back(std::make_unique<ui::LayersPanel>(session));
  panels.push_back(std::make_unique<ui::ComponentsPanel>(session));
  panels.push_back(std::make_unique<ui::MetricsPanel>(session));
  panels.push_back(std::make_unique<ui::PlaybackPanel>());
  return panels;
}

}  // namespace mostyle::test
