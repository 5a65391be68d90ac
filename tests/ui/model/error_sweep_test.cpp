// The error curve against k (ui/model/error_sweep.h) through the editor's engine link over the
// bundled pair: the shown decomposition's point, then one per k of the sweep, sorted; a new
// sparsity starts a curve of its own; new takes clear it; three takes have theirs too.
#include <algorithm>
#include <iterator>

#include <catch2/catch.hpp>

#include "tests/test_data.h"
#include "tests/ui/loaded_takes.h"

using namespace mostyle;
using namespace mostyle::ui;
using test::LoadedTakes;

namespace {

int points_at(const std::vector<ErrorPoint>& curve, double sparsity) {
  return static_cast<int>(std::count_if(curve.begin(), curve.end(), [&](const ErrorPoint& e) { return e.sparsity == sparsity; }));
}

}  // namespace

TEST_CASE("error sweep: every k of the sweep and the one shown, by k, the shown one as decomposed") {
  LoadedTakes s;  // k 6, sparsity 0.2: waited for, sweep included
  CHECK_FALSE(s.engine.sweeping());
  const std::vector<ErrorPoint>& curve = s.engine.error_curve();
  REQUIRE(curve.size() == std::size(ErrorSweep::kComponents));  // 6 is one of the sweep's
  for (size_t i = 0; i < curve.size(); ++i) {
    CHECK(curve[i].components == ErrorSweep::kComponents[i]);
    CHECK(curve[i].sparsity == 0.2);
    REQUIRE(curve[i].rmse.size() == 2);
    CHECK(curve[i].rmse[0] > 0.0);
    CHECK(curve[i].rmse[1] > 0.0);
  }
  // More components fit better (each its own decomposition: allow a little noise).
  CHECK(curve.back().rmse[0] < curve.front().rmse[0]);
  const Decomposed& shown = *s.engine.snapshot().decomposed;
  const auto six = std::find_if(curve.begin(), curve.end(), [](const ErrorPoint& e) { return e.components == 6; });
  REQUIRE(six != curve.end());
  CHECK(six->rmse == shown.rmse);

  // Another sparsity: a curve of its own beside the first.
  s.state.document.parameters.sparsity = 0.3;
  s.engine.wait_idle(s.state);
  CHECK(points_at(s.engine.error_curve(), 0.3) == static_cast<int>(std::size(ErrorSweep::kComponents)));
  CHECK(points_at(s.engine.error_curve(), 0.2) == static_cast<int>(std::size(ErrorSweep::kComponents)));

  // New takes: the curve is theirs alone.
  s.engine.load(test::asset("motions/cmu142_walk_joy.bvh"), test::asset("motions/cmu142_walk_happy.bvh"));
  s.engine.wait_idle(s.state);
  CHECK(points_at(s.engine.error_curve(), 0.2) == 0);
  CHECK(points_at(s.engine.error_curve(), 0.3) == static_cast<int>(std::size(ErrorSweep::kComponents)));

  // Three takes: a curve of their own, a fit error per take.
  s.engine.load_files({test::asset("motions/cmu142_walk_happy.bvh"), test::asset("motions/cmu142_walk_marching.bvh"),
                        test::asset("motions/cmu142_walk_joy.bvh")});
  s.engine.wait_idle(s.state);
  REQUIRE(s.engine.takes() != nullptr);
  CHECK_FALSE(s.engine.sweeping());
  CHECK(points_at(s.engine.error_curve(), 0.3) == static_cast<int>(std::size(ErrorSweep::kComponents)));
  for (const ErrorPoint& e : s.engine.error_curve()) CHECK(e.rmse.size() == 3);
}
