// The engine link (ui/model/blend_session.h): sync() brings the engine to the document, doing what
// the one list of fields (ui/model/document_fields.h) says each change makes stale, and nothing
// more: a weight re-mixes on this thread, k re-decomposes (not while its slider is held), an
// alignment option re-aligns, a view option asks the worker for nothing; keys are mixed on this
// thread like a weight, and a sentence of the engine's says where it refuses them.
#include <catch2/catch.hpp>

#include "tests/ui/loaded_session.h"
#include "ui/model/document_fields.h"
#include "ui/model/layer_parts.h"

using namespace mostyle;
using namespace mostyle::ui;
using test::LoadedSession;

namespace {

// What the worker was asked since the last idle: nothing, a decomposition, or a load.
bool worker_asked(const BlendSession& s) {
  const WorkerStatus status = s.status();
  return status.stage != WorkerStage::kIdle || status.pending;
}

}  // namespace

TEST_CASE("engine link: each change does what its field makes stale, and nothing more") {
  LoadedSession s;
  REQUIRE(s.session.result() != nullptr);
  const void* prepared = s.session.snapshot().prepared.get();
  const void* decomposed = s.session.snapshot().decomposed.get();

  SECTION("a mix field: mixed again on this thread, the worker left alone") {
    const Eigen::MatrixXd before = s.session.result()->motion.world;
    set_pair_alpha(s.state.document, 0.9);
    s.session.sync(s.state);
    CHECK_FALSE(worker_asked(s.session));
    const Eigen::MatrixXd& after = s.session.result()->motion.world;  // the timing too: maybe another length
    CHECK((after.rows() != before.rows() || (after - before).norm() > 1e-6));
  }
  SECTION("a view field: nothing asked of the worker, the blend unchanged") {
    const Eigen::MatrixXd before = s.session.result()->motion.world;
    s.state.document.overlay = !s.state.document.overlay;
    s.state.document.controls.ghosts = true;
    s.session.sync(s.state);
    CHECK_FALSE(worker_asked(s.session));
    CHECK(s.session.result()->motion.world == before);
  }
  SECTION("a decomposition field: asked for once let go, not while held") {
    s.state.document.parameters.components = 4;
    s.session.sync(s.state, /*item_held=*/true);
    CHECK_FALSE(worker_asked(s.session));
    CHECK_FALSE(s.session.decomposition_outdated());
    s.session.sync(s.state);
    CHECK(s.session.decomposition_outdated());
    s.session.wait_idle(s.state);
    CHECK(s.session.snapshot().decomposed.get() != decomposed);
    CHECK(s.session.snapshot().decomposed->params.components == 4);
    CHECK(s.session.snapshot().prepared.get() == prepared);  // not aligned again
  }
  SECTION("an alignment field: the takes prepared again, then decomposed") {
    s.state.document.controls.align.on = AlignOn::kBody;
    s.session.sync(s.state);
    CHECK(worker_asked(s.session));
    s.session.wait_idle(s.state);
    REQUIRE(s.session.snapshot().prepared != nullptr);
    CHECK(s.session.snapshot().prepared.get() != prepared);
    CHECK(s.session.snapshot().prepared->takes[1].alignment.feature.on == AlignOn::kBody);
    // A second sync asks for nothing more.
    s.session.sync(s.state);
    CHECK_FALSE(worker_asked(s.session));
  }
  SECTION("a load is a command: the document's files follow once the takes arrive") {
    const std::vector<std::string> files = s.state.document.files;
    REQUIRE(files.size() == 2);
    s.session.load_files({files[1], files[0]});
    CHECK(s.session.load_waiting());
    CHECK(s.state.document.files == files);  // not there yet
    s.session.wait_idle(s.state);
    CHECK(s.state.document.files == std::vector<std::string>{files[1], files[0]});
  }
}

TEST_CASE("engine link: a pair's keys reach the mix, and where the engine refuses them its sentence is shown") {
  LoadedSession s;
  REQUIRE(s.session.result() != nullptr);
  Document& d = s.state.document;
  // Alpha 1 without keys, then alpha 0 with one key of alpha 1: the keys are what is mixed.
  set_pair_alpha(d, 1.0);
  s.session.sync(s.state);
  const Eigen::MatrixXd at_b = s.session.result()->motion.world;
  set_pair_alpha(d, 0.0);
  s.session.sync(s.state);
  REQUIRE_FALSE(s.session.result()->motion.world.isApprox(at_b));
  d.controls.keys = {WeightKey{1.0, {0.0, 1.0}}};
  s.session.sync(s.state);
  CHECK_FALSE(worker_asked(s.session));  // a mix field: mixed again on this thread
  CHECK(s.session.result_error().empty());
  const Eigen::MatrixXd& keyed = s.session.result()->motion.world;
  REQUIRE(keyed.rows() == at_b.rows());
  CHECK(keyed.isApprox(at_b, 1e-6));
  CHECK_THAT(s.state.takes[result_index(2)].label, Catch::Contains("keyed"));
  // Keys of three takes do not fit a pair: not mixed (alpha 0 again).
  d.controls.keys = {WeightKey{1.0, {0.0, 0.5, 0.5}}};
  s.session.sync(s.state);
  CHECK(s.session.result_error().empty());
  CHECK_FALSE(s.session.result()->motion.world.isApprox(at_b));
  // Keys with an alpha per body part: the engine refuses, says why, and the last blend stays.
  d.controls.keys = {WeightKey{1.0, {0.0, 1.0}}};
  d.controls.per_part = true;
  set_part_row(d, *s.session.snapshot().decomposed, BodyPart::kLegs, std::vector<double>{0.0, 1.0});
  const Eigen::MatrixXd before = s.session.result()->motion.world;
  s.session.sync(s.state);
  CHECK_THAT(s.session.result_error(), Catch::Contains("keyed in time"));
  CHECK(s.session.result()->motion.world == before);
  // Without the keys, the per-part alphas blend again.
  d.controls.keys.clear();
  s.session.sync(s.state);
  CHECK(s.session.result_error().empty());
}
