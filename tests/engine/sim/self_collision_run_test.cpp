// Self-collision in a run: a start that folds link 3 across link 1 is a
// collision of the arm with itself, in the frames and the summary, and the
// scenario's switch and overrides turn it off.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <rrlab/sim/simulator.hpp>

#include "engine/sim_helpers.hpp"

namespace rrlab {
namespace {

using nlohmann::json;

// Four 1 m links; q0 folds link 3 back across link 1. The hand holds still.
json folded_scenario() {
  const double deg = std::numbers::pi / 180;
  const std::vector<double> q0 = {0, 150 * deg, 150 * deg, 0};
  const std::vector<double> tip = test::planar_tip(1.0, q0);
  return {{"dt", 0.01},
          {"duration", 0.2},
          {"robot", test::planar_robot(4, 1.0, 0.05, q0)},
          {"task", {{"space", "xy"}, {"trajectory", {{"type", "polyline"}, {"points", {tip, tip}}}}}}};
}

TEST(SelfCollisionRun, AFoldedStartIsASelfCollisionOfTheRun) {
  const test::RunResult run = test::run_scenario(folded_scenario(), "pinv");
  const Summary& s = run.summary;
  EXPECT_TRUE(s.self_collided);
  EXPECT_TRUE(s.collided);
  EXPECT_FALSE(s.obstacle_collided);
  ASSERT_TRUE(s.min_self_distance.has_value());
  EXPECT_LT(*s.min_self_distance, 0);
  ASSERT_FALSE(run.frames.empty());
  const Frame& f = run.frames.front();
  EXPECT_TRUE(f.self_collided);
  EXPECT_FALSE(f.collided);
  EXPECT_EQ(f.self_link_a, 0);
  EXPECT_EQ(f.self_link_b, 2);
  EXPECT_LT(f.min_self_distance, 0);
  const json j = summary_to_json(s);
  EXPECT_EQ(j["format"], kSummaryFormat);
  EXPECT_EQ(j["self_collided"], true);
  EXPECT_EQ(j["collided"], true);
  EXPECT_EQ(j["obstacle_collided"], false);
  EXPECT_LT(j["min_self_distance"].get<double>(), 0);
}

TEST(SelfCollisionRun, AStraightArmDoesNotTouchItself) {
  json doc = folded_scenario();
  doc["robot"]["q0"] = {0.1, 0.1, 0.1, 0.1};
  const std::vector<double> tip = test::planar_tip(1.0, {0.1, 0.1, 0.1, 0.1});
  doc["task"]["trajectory"]["points"] = {tip, tip};
  const test::RunResult run = test::run_scenario(doc, "pinv");
  EXPECT_FALSE(run.summary.self_collided);
  EXPECT_FALSE(run.summary.collided);
  ASSERT_TRUE(run.summary.min_self_distance.has_value());
  EXPECT_GT(*run.summary.min_self_distance, 0.5);
}

TEST(SelfCollisionRun, SwitchedOffOrAllowedThePairIsNotACollision) {
  json off = folded_scenario();
  off["robot"]["self_collision"] = false;
  const test::RunResult unchecked = test::run_scenario(off, "pinv");
  EXPECT_FALSE(unchecked.summary.self_collided);
  EXPECT_FALSE(unchecked.summary.collided);
  EXPECT_FALSE(unchecked.summary.min_self_distance.has_value());
  EXPECT_TRUE(summary_to_json(unchecked.summary)["min_self_distance"].is_null());
  EXPECT_EQ(unchecked.frames.front().self_link_a, -1);
  EXPECT_TRUE(std::isinf(unchecked.frames.front().min_self_distance));

  json allowed = folded_scenario();
  allowed["robot"]["allowed_collisions"] = {{1, 3}};
  const test::RunResult run = test::run_scenario(allowed, "pinv");
  EXPECT_FALSE(run.summary.self_collided);
  ASSERT_TRUE(run.summary.min_self_distance.has_value());  // pairs (1, 4) and (2, 4) are still checked
  EXPECT_GT(*run.summary.min_self_distance, 0);
}

}  // namespace
}  // namespace rrlab
