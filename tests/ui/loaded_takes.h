#pragma once
// A EngineLink with the bundled pair (or two takes given) loaded and decomposed (small k,
// quick), and every editor panel over it, in the order the editor draws them: for the model,
// panel and layout tests.
#include <memory>
#include <string>
#include <vector>

#include "tests/test_data.h"
#include "ui/model/engine_link.h"
#include "ui/panels/components_panel.h"
#include "ui/panels/layers_panel.h"
#include "ui/panels/files_panel.h"
#include "ui/panels/metrics_panel.h"
#include "ui/panels/parameters_panel.h"
#include "ui/panels/playback_panel.h"
#include "ui/panels/takes_panel.h"

namespace mostyle::test {

struct LoadedTakes {
  ui::EditorState state;
  ui::EngineLink engine;
  LoadedTakes() : LoadedTakes(asset("motions/cmu142_walk_happy.bvh"), asset("motions/cmu142_walk_marching.bvh")) {}
  LoadedTakes(const std::string& a, const std::string& b) {
    state.document.parameters.components = 6;  // small and quick
    state.document.parameters.sparsity = 0.2;
    engine.load(a, b);
    engine.wait_idle(state);
  }
};

inline std::vector<std::unique_ptr<ui::Panel>> all_panels(ui::EngineLink& engine) {
  std::vector<std::unique_ptr<ui::Panel>> panels;
  panels.push_back(std::make_unique<ui::TakesPanel>());
  panels.push_back(std::make_unique<ui::ParametersPanel>(engine));
  panels.push_back(std::make_unique<ui::FilesPanel>(engine, asset("motions")));
  panels.push_back(std::make_unique<ui::LayersPanel>(engine));
  panels.push_back(std::make_unique<ui::ComponentsPanel>(engine));
  panels.push_back(std::make_unique<ui::MetricsPanel>(engine));
  panels.push_back(std::make_unique<ui::PlaybackPanel>());
  return panels;
}

}  // namespace mostyle::test
