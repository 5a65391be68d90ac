// A list of weight keys as the timeline edits it (ui/model/weight_keys_edit.h), worked by hand: a
// key set at a moment replaces the one there or goes in its place in time, a moved key stays
// between its neighbours, keys follow their takes into another order.
#include <vector>

#include <catch2/catch.hpp>

#include "ui/model/weight_keys_edit.h"

using namespace mostyle;
using namespace mostyle::ui;

namespace {

// A pair's keys: alpha a at each time.
WeightKeys pair_keys(const std::vector<std::pair<double, double>>& at) {
  WeightKeys keys;
  for (const auto& [seconds, alpha] : at) keys.push_back(WeightKey{seconds, {1.0 - alpha, alpha}});
  return keys;
}

std::vector<double> times(const WeightKeys& keys) {
  std::vector<double> t;
  for (const WeightKey& key : keys) t.push_back(key.seconds);
  return t;
}

constexpr double kHalfFrame = 0.5 / 30.0;  // seconds at 30 fps

}  // namespace

TEST_CASE("weight keys: compared key by key, and fit the takes they hold a weight for") {
  const WeightKeys keys = pair_keys({{0.0, 0.0}, {10.0, 1.0}});
  CHECK(same_keys(keys, pair_keys({{0.0, 0.0}, {10.0, 1.0}})));
  CHECK_FALSE(same_keys(keys, pair_keys({{0.0, 0.0}, {10.0, 0.9}})));    // a weight
  CHECK_FALSE(same_keys(keys, pair_keys({{0.0, 0.0}, {10.5, 1.0}})));    // a time
  CHECK_FALSE(same_keys(keys, pair_keys({{0.0, 0.0}})));                 // a key fewer
  CHECK(same_keys(WeightKeys(), WeightKeys()));
  CHECK(keys_fit(keys, 2));
  CHECK_FALSE(keys_fit(keys, 3));  // made for a pair: not for a palette of three
  CHECK_FALSE(keys_fit(WeightKeys(), 2));
  WeightKeys mixed = keys;
  mixed.push_back(WeightKey{12.0, {0.2, 0.3, 0.5}});
  CHECK_FALSE(keys_fit(mixed, 2));
  CHECK_FALSE(keys_fit(mixed, 3));
}

TEST_CASE("weight keys: the key near a moment is the nearest within the tolerance") {
  const WeightKeys keys = pair_keys({{1.0, 0.1}, {2.0, 0.2}, {4.0, 0.4}});
  CHECK(key_near(keys, 2.0, kHalfFrame) == 1);
  CHECK(key_near(keys, 2.0 + 0.9 * kHalfFrame, kHalfFrame) == 1);
  CHECK(key_near(keys, 2.0 + kHalfFrame, kHalfFrame) == 1);  // ends included
  CHECK(key_near(keys, 2.0 + 1.1 * kHalfFrame, kHalfFrame) == -1);
  CHECK(key_near(keys, 0.0, kHalfFrame) == -1);
  CHECK(key_near(keys, 9.0, kHalfFrame) == -1);
  CHECK(key_near(keys, 3.1, 1.0) == 2);  // 0.9 from 4, 1.1 from 2
  CHECK(key_near(keys, 2.9, 1.0) == 1);
  CHECK(key_near(WeightKeys(), 1.0, 1.0) == -1);
}

TEST_CASE("weight keys: setting a key replaces the one at that moment or adds one in its place") {
  WeightKeys keys = pair_keys({{1.0, 0.1}, {4.0, 0.4}});
  // Between the two: a new key, in order.
  CHECK(set_key(keys, 2.5, kHalfFrame, {0.75, 0.25}) == 1);
  CHECK(times(keys) == std::vector<double>{1.0, 2.5, 4.0});
  // Before the first and after the last.
  CHECK(set_key(keys, 0.0, kHalfFrame, {1.0, 0.0}) == 0);
  CHECK(set_key(keys, 9.0, kHalfFrame, {0.0, 1.0}) == 4);
  CHECK(times(keys) == std::vector<double>{0.0, 1.0, 2.5, 4.0, 9.0});
  // Within half a frame of a key: that key takes the weights and keeps its time.
  CHECK(set_key(keys, 4.0 + 0.5 * kHalfFrame, kHalfFrame, {0.5, 0.5}) == 3);
  CHECK(times(keys) == std::vector<double>{0.0, 1.0, 2.5, 4.0, 9.0});
  CHECK(keys[3].weights == std::vector<double>{0.5, 0.5});
  // Into an empty list.
  WeightKeys none;
  CHECK(set_key(none, 3.0, kHalfFrame, {0.3, 0.7}) == 0);
  CHECK(same_keys(none, {WeightKey{3.0, {0.3, 0.7}}}));
}

TEST_CASE("weight keys: a moved key stays between its neighbours and on the result") {
  const double frame = 1.0 / 30.0;
  WeightKeys keys = pair_keys({{1.0, 0.1}, {2.0, 0.2}, {4.0, 0.4}});
  CHECK(move_key(keys, 1, 3.0, frame, 10.0) == 3.0);           // free between 1 and 4
  CHECK(move_key(keys, 1, 5.0, frame, 10.0) == Approx(4.0 - frame));  // not past the next
  CHECK(move_key(keys, 1, 0.2, frame, 10.0) == Approx(1.0 + frame));  // nor before the previous
  CHECK(times(keys)[0] == 1.0);
  CHECK(times(keys)[2] == 4.0);
  CHECK(move_key(keys, 0, -3.0, frame, 10.0) == 0.0);          // not before the result's start
  CHECK(move_key(keys, 2, 30.0, frame, 10.0) == 10.0);         // nor past its end
  CHECK(keys[1].weights == std::vector<double>{0.8, 0.2});     // a move keeps the weights
  // No room between the neighbours: it stays where it is.
  WeightKeys tight = pair_keys({{1.0, 0.1}, {1.0 + frame, 0.2}, {1.0 + 2.0 * frame, 0.4}});
  CHECK(move_key(tight, 1, 3.0, 1.5 * frame, 10.0) == 1.0 + frame);
}

TEST_CASE("weight keys: each key's weights follow their takes into another order") {
  // Takes: normal, tired, proud; making proud (2) the first.
  const WeightKeys keys = {WeightKey{0.0, {1.0, 0.0, 0.0}}, WeightKey{10.0, {0.2, 0.7, 0.1}},
                           WeightKey{12.0, {0.5, 0.5}}};  // made for a pair: left alone
  const WeightKeys r = reorder_keys(keys, {2, 0, 1});
  CHECK(r[0].weights == std::vector<double>{0.0, 1.0, 0.0});
  CHECK(r[1].weights == std::vector<double>{0.1, 0.2, 0.7});
  CHECK(r[2].weights == std::vector<double>{0.5, 0.5});
  CHECK(times(r) == times(keys));
  CHECK(same_keys(reorder_keys(r, {1, 2, 0}), keys));  // and back
}
