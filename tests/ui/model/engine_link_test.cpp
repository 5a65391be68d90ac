// The engine link (ui/model/engine_link.h): sync() brings the engine to the document, doing what
// the one list of fields (ui/model/document_fields.h) says each change makes stale, and nothing
// more: a weight re-mixes on this thread, k re-decomposes (not while its slider is held), an
// alignment option re-aligns, a view option asks the worker for nothing; keys are mixed on this
// thread like a weight, and a sentence of the engine's says where it refuses them.
#include <catch2/catch.hpp>

#include "tests/ui/loaded_takes.h"
#include "ui/model/document_fields.h"
#include "ui/model/layer_parts.h"

using namespace mostyle;
using namespace mostyle::ui;
using test::LoadedTakes;

namespace {

// What the worker was asked since the last idle: nothing, a decomposition, or a load.
bool worker_asked(const EngineLink& s) {
  const WorkerStatus status = s.status();
  return status.stage != WorkerStage::kIdle || status.pending;
}

}  // namespace

TEST_CASE("engine link: each change does what its field makes stale, and nothing more") {
  LoadedTakes s;
  REQUIRE(s.engine.result() != nullptr);
  const void* prepared = s.engine.snapshot().prepared.get();
  const void* decomposed = s.engine.snapshot().decomposed.get();

  SECTION("a mix field: mixed again on this thread, the worker left alone") {
    const Eigen::MatrixXd before = s.engine.result()->motion.world;
    set_pair_alpha(s.state.document, 0.9);
    s.engine.sync(s.state);
    CHECK_FALSE(worker_asked(s.engine));
    const Eigen::MatrixXd& after = s.engine.result()->motion.world;  // the timing too: maybe another length
    CHECK((after.rows() != before.rows() || (after - before).norm() > 1e-6));
  }
  SECTION("a view field: nothing asked of the worker, the blend unchanged") {
    const Eigen::MatrixXd before = s.engine.result()->motion.world;
    s.state.document.overlay = !s.state.document.overlay;
    s.state.document.controls.ghosts = true;
    s.engine.sync(s.state);
    CHECK_FALSE(worker_asked(s.engine));
    CHECK(s.engine.result()->motion.world == before);
  }
  SECTION("a decomposition field: asked for once let go, not while held") {
    s.state.document.parameters.components = 4;
    s.engine.sync(s.state, /*item_held=*/true);
    CHECK_FALSE(worker_asked(s.engine));
    CHECK_FALSE(s.engine.decomposition_outdated());
    s.engine.sync(s.state);
    CHECK(s.engine.decomposition_outdated());
    s.engine.wait_idle(s.state);
    CHECK(s.engine.snapshot().decomposed.get() != decomposed);
    CHECK(s.engine.snapshot().decomposed->params.components == 4);
    CHECK(s.engine.snapshot().prepared.get() == prepared);  // not aligned again
  }
  SECTION("an alignment field: the takes prepared again, then decomposed") {
    s.state.document.controls.align.on = AlignOn::kBody;
    s.engine.sync(s.state);
    CHECK(worker_asked(s.engine));
    s.engine.wait_idle(s.state);
    REQUIRE(s.engine.snapshot().prepared != nullptr);
    CHECK(s.engine.snapshot().prepared.get() != prepared);
    CHECK(s.engine.snapshot().prepared->takes[1].alignment.feature.on == AlignOn::kBody);
    // A second sync asks for nothing more.
    s.engine.sync(s.state);
    CHECK_FALSE(worker_asked(s.engine));
  }
  SECTION("a load is a command: the document's files follow once the takes arrive") {
    const std::vector<std::string> files = s.state.document.files;
    REQUIRE(files.size() == 2);
    s.engine.load_files({files[1], files[0]});
    CHECK(s.engine.load_waiting());
    CHECK(s.state.document.files == files);  // not there yet
    s.engine.wait_idle(s.state);
    CHECK(s.state.document.files == std::vector<std::string>{files[1], files[0]});
  }
}

TEST_CASE("engine link: a pair's keys reach the mix, and where the engine refuses them its sentence is shown") {
  LoadedTakes s;
  REQUIRE(s.engine.result() != nullptr);
  Document& d = s.state.document;
  // Alpha 1 without keys, then alpha 0 with one key of alpha 1: the keys are what is mixed.
  set_pair_alpha(d, 1.0);
  s.engine.sync(s.state);
  const Eigen::MatrixXd at_b = s.engine.result()->motion.world;
  set_pair_alpha(d, 0.0);
  s.engine.sync(s.state);
  // Another result (another length too, where A and B walk different counts of cycles).
  const Eigen::MatrixXd& at_a = s.engine.result()->motion.world;
  REQUIRE_FALSE((at_a.rows() == at_b.rows() && at_a.isApprox(at_b)));
  d.controls.keys = {WeightKey{1.0, {0.0, 1.0}}};
  s.engine.sync(s.state);
  CHECK_FALSE(worker_asked(s.engine));  // a mix field: mixed again on this thread
  CHECK(s.engine.result_error().empty());
  const Eigen::MatrixXd& keyed = s.engine.result()->motion.world;
  REQUIRE(keyed.rows() == at_b.rows());
  CHECK(keyed.isApprox(at_b, 1e-6));
  CHECK_THAT(s.state.shown[result_index(2)].label, Catch::Contains("keyed"));
  // Keys of three takes do not fit a pair: not mixed (alpha 0 again).
  d.controls.keys = {WeightKey{1.0, {0.0, 0.5, 0.5}}};
  s.engine.sync(s.state);
  CHECK(s.engine.result_error().empty());
  const Eigen::MatrixXd& again = s.engine.result()->motion.world;
  CHECK_FALSE((again.rows() == at_b.rows() && again.isApprox(at_b)));
  // Keys with an alpha per body part: the engine refuses, says why, and the last blend stays.
  d.controls.keys = {WeightKey{1.0, {0.0, 1.0}}};
  d.controls.per_part = true;
  set_part_row(d, *s.engine.snapshot().decomposed, BodyPart::kLegs, std::vector<double>{0.0, 1.0});
  const Eigen::MatrixXd before = s.engine.result()->motion.world;
  s.engine.sync(s.state);
  CHECK_THAT(s.engine.result_error(), Catch::Contains("keyed in time"));
  CHECK(s.engine.result()->motion.world == before);
  // Without the keys, the per-part alphas blend again.
  d.controls.keys.clear();
  s.engine.sync(s.state);
  CHECK(s.engine.result_error().empty());
}
