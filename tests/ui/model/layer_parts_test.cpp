// The layers' weights per body part and per component (ui/model/layer_parts.h), on a
// decomposition made by hand (its components' regions only), and their fit to a new
// decomposition (ui/model/document_mix.h fit_component_weights): one rule for any number of takes.
#include <catch2/catch.hpp>

#include "ui/model/document_mix.h"
#include "ui/model/layer_parts.h"

using namespace mostyle;
using namespace mostyle::ui;

namespace {

// k components, one per region given, in order.
Decomposed decomposed_on(std::vector<BodyRegion> regions) {
  Decomposed d;
  d.params.components = static_cast<int>(regions.size());
  for (BodyRegion r : regions) d.component_joints.push_back(ComponentJoints{{}, -1, r, body_region_name(r)});
  return d;
}

Document with_weights(std::vector<double> weights) {
  Document doc;
  set_layer_weights(doc, weights);
  return doc;
}

}  // namespace

TEST_CASE("layer parts: a part's row is set on each of its components, and cleared again") {
  const Decomposed d = decomposed_on({BodyRegion::kLeftLeg, BodyRegion::kRightArm, BodyRegion::kSpineAndHead,
                                      BodyRegion::kRightLeg});
  for (int takes : {2, 3}) {
    INFO(takes << " takes");
    Document doc = with_weights(std::vector<double>(static_cast<size_t>(takes), 1.0 / takes));
    std::vector<double> row(static_cast<size_t>(takes), 0.0);
    row.back() = 1.0;
    set_part_row(doc, d, BodyPart::kLegs, row);
    CHECK(component_set(doc, 0));
    CHECK(component_set(doc, 3));
    CHECK_FALSE(component_set(doc, 1));
    CHECK(component_row(doc, 3, layer_weights(doc)) == row);
    CHECK(component_row(doc, 1, layer_weights(doc)) == layer_weights(doc));  // the layers' weights there
    CHECK(part_from_take(doc, d, BodyPart::kLegs) == takes - 1);
    CHECK(part_from_take(doc, d, BodyPart::kArms) == -1);
    CHECK(first_component_of(d, BodyPart::kArms) == 1);
    CHECK(doc.controls.component_regions.size() == 4);  // the regions they were set on
    set_part_row(doc, d, BodyPart::kLegs, std::nullopt);
    CHECK_FALSE(component_set(doc, 0));
    CHECK(part_from_take(doc, d, BodyPart::kLegs) == -1);
  }
}

TEST_CASE("layer parts: a new decomposition's components take the weights of their region's first") {
  const Decomposed before = decomposed_on({BodyRegion::kLeftLeg, BodyRegion::kSpineAndHead});
  Document doc = with_weights({0.5, 0.5});
  set_component_row(doc, before, 0, std::vector<double>{0.2, 0.8});
  const Decomposed after = decomposed_on({BodyRegion::kSpineAndHead, BodyRegion::kRightArm, BodyRegion::kLeftLeg,
                                          BodyRegion::kLeftLeg});
  fit_component_weights(doc, after);
  CHECK_FALSE(component_set(doc, 0));
  CHECK_FALSE(component_set(doc, 1));
  CHECK(component_row(doc, 2, layer_weights(doc)) == std::vector<double>{0.2, 0.8});
  CHECK(component_row(doc, 3, layer_weights(doc)) == std::vector<double>{0.2, 0.8});
  CHECK(doc.controls.component_regions.size() == 4);
}

TEST_CASE("layer parts: a weight set keeps the sum at 1 within the mix's range") {
  const std::vector<double> w = set_weight_keeping_sum({0.2, 0.3, 0.5}, 0, 0.6);
  CHECK(w[0] == Approx(0.6));
  CHECK(w[1] / w[2] == Approx(0.6));  // the others keep their proportions
  CHECK(w[0] + w[1] + w[2] == Approx(1.0));
  const std::vector<double> even = set_weight_keeping_sum({1.0, 0.0, 0.0}, 0, 0.4);
  CHECK(even[1] == Approx(0.3));  // the others summed to 0: the rest shared equally
  CHECK(even[2] == Approx(0.3));
}
