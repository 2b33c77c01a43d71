// Running scenarios in tests: inline JSON in, frames and summary out.
#pragma once

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <vector>

#include <rrlab/methods/registry.hpp>
#include <rrlab/scenario/scenario.hpp>
#include <rrlab/sim/simulator.hpp>

namespace rrlab::test {

struct FrameLog final : Recorder {
  std::vector<Frame> frames;
  void frame(const Frame& f) override { frames.push_back(f); }
};

struct RunResult {
  Summary summary;
  std::vector<Frame> frames;
  double max_abs_qdot() const {
    double m = 0;
    for (const Frame& f : frames) m = std::max(m, f.qdot.cwiseAbs().maxCoeff());
    return m;
  }
  // Largest tracking error from frame `from` on.
  double max_error_after(size_t from) const {
    double m = 0;
    for (size_t i = from; i < frames.size(); ++i) m = std::max(m, frames[i].task_error);
    return m;
  }
};

inline RunResult run_scenario(nlohmann::json doc, const std::string& method,
                              const nlohmann::json& params = nlohmann::json::object()) {
  doc["method"] = {{"name", method}, {"params", params}};
  Simulator sim(parse_scenario(doc));
  FrameLog log;
  RunResult r;
  r.summary = run_to_end(sim, &log);
  r.frames = std::move(log.frames);
  return r;
}

// Runs to the end, resets, runs again: both runs must give the same q and
// diagnostics bit for bit (a method's internal state starts over on reset).
inline void expect_repeats_after_reset(Simulator& sim) {
  FrameLog first, second;
  run_to_end(sim, &first);
  sim.reset();
  run_to_end(sim, &second);
  ASSERT_EQ(first.frames.size(), second.frames.size());
  for (size_t i = 0; i < first.frames.size(); ++i) {
    ASSERT_EQ(first.frames[i].q, second.frames[i].q) << i;
    ASSERT_EQ(first.frames[i].diagnostics, second.frames[i].diagnostics) << i;
  }
}

// Steps `sim` and, after each step, compares the method's q̇ with pinv's
// minimum-norm q̇ on the same inputs: the difference (the null-space part) must
// not move the end-effector, ‖J q̇_N‖ < 1e-9. Returns the largest ‖q̇_N‖ seen.
inline double largest_null_space_motion(Simulator& sim, int steps, const std::string& label = "") {
  const MethodContext ctx{sim.model(), sim.scenario().task.space, int(sim.scene().obstacles.size())};
  auto pinv = find_method("pinv")->make(ctx);
  StepOutput minimum_norm;
  minimum_norm.qdot.resize(sim.model().dof());
  minimum_norm.diag.values.resize(1);
  double largest_null = 0;
  for (int k = 0; k < steps; ++k) {
    sim.step();
    // same inputs as the step just taken: the Jacobian at q_k, the reference at t_k
    const StepInput in{sim.model(), State{sim.frame().t, sim.frame().step, sim.frame().q, sim.frame().qdot},
                       sim.reference(), sim.scene(), sim.scenario().dt, sim.kinematics(), sim.task_jacobian(),
                       sim.distances(), sim.task(), sim.self_distances()};
    pinv->step(in, minimum_norm);
    const Eigen::VectorXd null_motion = sim.frame().qdot - minimum_norm.qdot;
    largest_null = std::max(largest_null, null_motion.norm());
    EXPECT_LT((sim.task_jacobian() * null_motion).norm(), 1e-9) << label << " step " << k;
  }
  return largest_null;
}

// Planar chain of `n` equal links; q0 in radians.
inline nlohmann::json planar_robot(int n, double length, double radius, const std::vector<double>& q0) {
  nlohmann::json links = nlohmann::json::array();
  for (int i = 0; i < n; ++i) links.push_back({{"length", length}, {"radius", radius}});
  return {{"kind", "planar"}, {"base", {0, 0}}, {"links", links}, {"q0", q0}};
}

// End-effector of a planar chain at q (relative angles from +x).
inline std::vector<double> planar_tip(double length, const std::vector<double>& q) {
  double a = 0, x = 0, y = 0;
  for (double qi : q) {
    a += qi;
    x += length * std::cos(a);
    y += length * std::sin(a);
  }
  return {x, y};
}

}  // namespace rrlab::test
