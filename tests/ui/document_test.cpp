// The editor's document (ui/document.h): a palette's per-take values follow their takes.
#include "ui/document.h"

#include <catch2/catch.hpp>

using namespace mostyle::ui;

TEST_CASE("reorder_takes: each take keeps its weight, per-part weights and strength when the content changes") {
  // Takes: normal (content), tired, proud, old. Making "proud" (2) the content moves it first.
  PaletteControls c;
  c.weights = {0.63, 0.08, 0.2, 0.09};
  c.part_weights = {{1, 0, 0, 0}, {}, {0, 0, 0.5, 0.5}};
  c.strengths = {0.0, 1.5, -1.0, 0.7};
  c.neutral = 3;  // old
  c.transfer = true;
  const std::vector<int> order = {2, 0, 1, 3};  // proud, normal, tired, old
  const PaletteControls r = reorder_takes(c, order);
  CHECK(r.weights == std::vector<double>{0.2, 0.63, 0.08, 0.09});
  CHECK(r.part_weights[0] == std::vector<double>{0, 1, 0, 0});
  CHECK(r.part_weights[1].empty());  // "the weights": nothing to reorder
  CHECK(r.part_weights[2] == std::vector<double>{0.5, 0, 0, 0.5});
  CHECK(r.strengths == std::vector<double>{-1.0, 0.0, 1.5, 0.7});
  CHECK(r.neutral == 3);
  CHECK(r.transfer);
  // And back: the inverse order gives the controls we started from.
  std::vector<int> inverse(order.size());
  for (size_t k = 0; k < order.size(); ++k) inverse[static_cast<size_t>(order[k])] = static_cast<int>(k);
  CHECK(reorder_takes(r, inverse) == c);
  // The neutral moves with its take; values not sized for these takes are left alone.
  c.neutral = 1;
  c.weights = {0.5, 0.5};
  const PaletteControls moved = reorder_takes(c, {1, 2, 0, 3});
  CHECK(moved.neutral == 0);
  CHECK(moved.weights == std::vector<double>{0.5, 0.5});
}
