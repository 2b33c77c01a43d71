// Scenarios and a checked runner for the tests of qp_ik, hqp and diffik
// (methods over velocity_constraints): every frame's state and the state
// after the last integration are checked for collisions and limits.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "engine/sim_helpers.hpp"

namespace rrlab::test {

// A planar chain of `n` links of `length`, its hand moving in a straight line
// (quintic) from where it starts to `target` over `duration`.
inline nlohmann::json planar_reach(int n, double length, double radius, const std::vector<double>& q0,
                                   const std::vector<double>& target, double duration) {
  nlohmann::json doc = {{"dt", 0.01}, {"duration", duration}, {"robot", planar_robot(n, length, radius, q0)}};
  doc["task"] = {{"space", "xy"},
                 {"trajectory",
                  {{"type", "polyline"}, {"points", {planar_tip(length, q0), target}}, {"time_law", "quintic"}}}};
  return doc;
}

// Link 3 of a 4-link arm sweeps through a point post on the way down (pinv
// passes 0.02 m into it).
inline nlohmann::json post_in_the_way() {
  nlohmann::json doc = planar_reach(4, 0.5, 0.02, {0.9, -0.6, -0.6, -0.3}, {1.0, -0.6}, 4.0);
  doc["obstacles"] = {{{"id", "post"}, {"shape", "point"}, {"position", {0.93, 0.15}}}};
  return doc;
}

// The hand is asked onto the base link: pinv folds link 4 into link 1.
inline nlohmann::json folding_onto_itself() {
  return planar_reach(4, 0.5, 0.03, {0.5, 1.8, 1.8, 1.0}, {0.25, 0.0}, 3.0);
}

// A target past the joint ranges (pinv crosses joints 2 and 3 by 0.44 rad).
inline nlohmann::json target_past_the_limits() {
  nlohmann::json doc = planar_reach(3, 0.5, 0.02, {0.3, 0.3, 0.3}, {0.2, 1.1}, 3.0);
  doc["robot"]["limits"] = {{"lower", {-1.0, -0.5, -0.5}}, {"upper", {1.0, 0.5, 0.5}}};
  return doc;
}

// The 4-link arm on a circle of radius 0.3 m (no obstacles), its joints
// limited to `speed` rad/s when `speed` > 0.
inline nlohmann::json circle_at_speed(double speed) {
  nlohmann::json doc = {{"dt", 0.01},
                        {"duration", 6.0},
                        {"robot", planar_robot(4, 0.5, 0.02, {0.2, 0.6, 0.5, 0.4})},
                        {"task", {{"space", "xy"},
                                  {"trajectory", {{"type", "circle"}, {"center", {0.9, 0.9}}, {"radius", 0.3}}}}}};
  if (speed > 0) doc["robot"]["limits"] = {{"velocity", {speed, speed, speed, speed}}};
  return doc;
}

// A ball thrown at the arm's third link faster than its joints (0.2 rad/s)
// can take it away: the dampers cannot all hold.
inline nlohmann::json ball_faster_than_the_arm() {
  nlohmann::json doc = planar_reach(4, 0.5, 0.02, {0.9, -0.6, -0.6, -0.3}, {1.5, 0.0}, 2.0);
  doc["robot"]["limits"] = {{"velocity", {0.2, 0.2, 0.2, 0.2}}};
  doc["obstacles"] = {{{"id", "ball"}, {"shape", "sphere"}, {"center", {1.05, 1.0}}, {"radius", 0.05},
                       {"velocity", {0.0, -1.0}}}};
  return doc;
}

struct CheckedRun {
  Summary summary;
  std::vector<Frame> frames;
  std::vector<std::string> diag_names;
  int collided_states = 0, self_collided_states = 0, limit_crossed_states = 0;  // frames + the final state
  double min_distance = INFINITY, min_self_distance = INFINITY;
  double diag(size_t frame, const std::string& name) const {
    for (size_t i = 0; i < diag_names.size(); ++i)
      if (diag_names[i] == name) return frames[frame].diagnostics[Eigen::Index(i)];
    ADD_FAILURE() << "no diagnostic " << name;
    return NAN;
  }
  bool safe() const { return collided_states == 0 && self_collided_states == 0 && limit_crossed_states == 0; }
};

// Runs `doc` with `method` to the end, then takes one more step so the state
// the last integration reached is measured too (its frame is the last one).
inline CheckedRun checked_run(nlohmann::json doc, const std::string& method,
                              const nlohmann::json& params = nlohmann::json::object()) {
  doc["method"] = {{"name", method}, {"params", params}};
  Simulator sim(parse_scenario(doc));
  FrameLog log;
  CheckedRun r;
  r.summary = run_to_end(sim, &log);
  sim.set_total_steps(sim.total_steps() + 1);
  sim.step();
  log.frames.push_back(sim.frame());
  r.frames = std::move(log.frames);
  r.diag_names = sim.diagnostic_names();
  for (const Frame& f : r.frames) {
    r.collided_states += f.collided;
    r.self_collided_states += f.self_collided;
    r.limit_crossed_states += f.joint_limit_margin < 0;
    r.min_distance = std::min(r.min_distance, f.min_distance);
    r.min_self_distance = std::min(r.min_self_distance, f.min_self_distance);
  }
  return r;
}

}  // namespace rrlab::test
