// Qiu, Cao & Sun: the paper's two examples (scenarios 20, 21) and the
// properties of the QP resolution (bounds, obstacle margin, singularity
// revision, relaxation when infeasible).
#include <gtest/gtest.h>

#include "engine/sim_helpers.hpp"
#include "engine/test_models.hpp"
#include "methods/registry.hpp"

namespace rrlab {
namespace {

using nlohmann::json;
using test::run_scenario;

struct FileRun {
  Summary summary;
  std::vector<Frame> frames;
  std::vector<std::string> diag_names;
  double diag(size_t frame, const std::string& name) const {
    for (size_t i = 0; i < diag_names.size(); ++i)
      if (diag_names[i] == name) return frames[frame].diagnostics[static_cast<Eigen::Index>(i)];
    ADD_FAILURE() << "no diagnostic " << name;
    return 0;
  }
  double peak_joint_speed() const {
    double m = 0;
    for (const Frame& f : frames) m = std::max(m, f.qdot.cwiseAbs().maxCoeff());
    return m;
  }
};

FileRun run_file(const std::string& file, const std::string& method) {
  Simulator sim(load_scenario_file(test::source_path(file)), method);
  test::FrameLog log;
  FileRun r;
  r.summary = run_to_end(sim, &log);
  r.frames = std::move(log.frames);
  r.diag_names = sim.diagnostic_names();
  return r;
}

TEST(QpConstraints, QiuCirclePseudoinverseCollides) {
  const FileRun pinv = run_file("scenarios/20_qiu_circle.json", "pinv");
  EXPECT_TRUE(pinv.summary.collided);
  EXPECT_LE(pinv.summary.min_distance, 0.0);
}

TEST(QpConstraints, QiuCircleKeepsTheSafetyMarginAndEveryBound) {
  const FileRun qp = run_file("scenarios/20_qiu_circle.json", "qp_constraints");
  const double d_s = 0.1;
  EXPECT_FALSE(qp.summary.collided);
  EXPECT_GE(qp.summary.min_distance, d_s - 1e-3);
  EXPECT_FALSE(qp.summary.joint_limit_violated);
  ASSERT_TRUE(qp.summary.max_qdot_ratio && qp.summary.max_qddot_ratio);
  EXPECT_LE(*qp.summary.max_qdot_ratio, 1.0);
  EXPECT_LE(*qp.summary.max_qddot_ratio, 1.0);
  EXPECT_EQ(qp.summary.nonfinite_steps, 0);
  // the circle is tracked: exactly away from the obstacle, with a reported
  // excursion while the links slide around it (task relaxed, see README)
  EXPECT_LT(qp.summary.final_tracking_error, 1e-4);
  EXPECT_LT(qp.summary.max_tracking_error, 0.2);
  double exact_steps = 0;
  for (size_t i = 0; i < qp.frames.size(); ++i) exact_steps += qp.diag(i, "relaxation") == 0;
  EXPECT_GT(exact_steps / qp.frames.size(), 0.75);
  RecordProperty("max_tracking_error_m", std::to_string(qp.summary.max_tracking_error));
  RecordProperty("min_distance_m", std::to_string(qp.summary.min_distance));
  std::printf("qiu circle: qp max tracking error %.4f m, min distance %.4f m, exact-task steps %.0f%%\n",
              qp.summary.max_tracking_error, qp.summary.min_distance, 100 * exact_steps / qp.frames.size());
}

TEST(QpConstraints, ClearanceGainMovesLinksAwayBeforeTheRowsBind) {
  // eq 8's linear term (an extension, 0 in the scenario): less task relaxation
  Simulator plain(load_scenario_file(test::source_path("scenarios/20_qiu_circle.json")));
  Simulator pushed(load_scenario_file(test::source_path("scenarios/20_qiu_circle.json")));
  pushed.set_param("clearance_gain", 10.0);
  const Summary a = run_to_end(plain, nullptr), b = run_to_end(pushed, nullptr);
  EXPECT_GE(b.min_distance, 0.1 - 1e-3);
  EXPECT_GT(b.min_distance, a.min_distance);
  EXPECT_LT(b.max_tracking_error, 0.5 * a.max_tracking_error);
  EXPECT_LE(*b.max_qddot_ratio, 1.0);
  std::printf("qiu circle with clearance_gain 10: max tracking error %.4f m (paper objective %.4f), min distance %.4f m\n",
              b.max_tracking_error, a.max_tracking_error, b.min_distance);
}

TEST(QpConstraints, QiuEllipsePseudoinverseBlowsUpWhereQpBypassesTheSingularity) {
  const FileRun pinv = run_file("scenarios/21_qiu_ellipse.json", "pinv");
  const FileRun qp = run_file("scenarios/21_qiu_ellipse.json", "qp_constraints");
  const double sigma_s = 0.06;
  EXPECT_GT(pinv.peak_joint_speed(), 50.0);  // far beyond every joint's limit
  EXPECT_LE(*qp.summary.max_qdot_ratio, 1.0);
  EXPECT_LE(*qp.summary.max_qddot_ratio, 1.0);
  double min_sigma = 1e9;
  int revised = 0;
  for (size_t i = 0; i < qp.frames.size(); ++i) {
    min_sigma = std::min(min_sigma, qp.diag(i, "sigma_min"));
    revised += qp.diag(i, "singularity_revision") > 0;
  }
  EXPECT_GT(min_sigma, 0.5 * sigma_s);  // held near σ_s (one step of overshoot)
  EXPECT_GT(revised, 0);
  EXPECT_LT(qp.summary.max_tracking_error, 0.05);
  EXPECT_LT(qp.summary.final_tracking_error, 1e-3);
  std::printf("qiu ellipse: pinv peak joint speed %.1f rad/s; qp peak %.3f rad/s, min sigma %.4f, max error %.4f m\n",
              pinv.peak_joint_speed(), qp.peak_joint_speed(), min_sigma, qp.summary.max_tracking_error);
}

// Redundant planar 4-link arm on a circle, nothing near: the QP is the
// minimum-norm solution, i.e. the pseudoinverse.
json free_circle() {
  return {{"dt", 0.01},
          {"duration", 1.0},
          {"robot", test::planar_robot(4, 0.5, 0.02, {0.2, 0.6, 0.5, 0.4})},
          {"task", {{"space", "xy"}, {"trajectory", {{"type", "circle"}, {"center", {0.9, 0.9}}, {"radius", 0.3}}}}}};
}

TEST(QpConstraints, WithoutActiveConstraintsItIsThePseudoinverse) {
  const auto qp = run_scenario(free_circle(), "qp_constraints", {{"sigma_s", 0.0}});
  const auto pinv = run_scenario(free_circle(), "pinv");
  ASSERT_EQ(qp.frames.size(), pinv.frames.size());
  for (size_t i = 0; i < qp.frames.size(); ++i)
    EXPECT_LT((qp.frames[i].qdot - pinv.frames[i].qdot).norm(), 1e-9) << i;
}

TEST(QpConstraints, InfeasibleTaskIsRelaxedNeverNan) {
  json doc = free_circle();
  doc["robot"]["limits"] = {{"velocity", {0.05, 0.05, 0.05, 0.05}}, {"acceleration", {1, 1, 1, 1}}};
  const auto r = run_scenario(doc, "qp_constraints");
  EXPECT_EQ(r.summary.nonfinite_steps, 0);
  EXPECT_LE(*r.summary.max_qdot_ratio, 1.0);
  EXPECT_LE(*r.summary.max_qddot_ratio, 1.0);
  Simulator sim(parse_scenario([&] {
    json d = doc;
    d["method"] = {{"name", "qp_constraints"}};
    return d;
  }()));
  sim.step();
  sim.step();
  const auto& names = sim.diagnostic_names();
  const auto at = std::find(names.begin(), names.end(), "relaxation") - names.begin();
  EXPECT_GE(sim.frame().diagnostics[at], 1.0);
  EXPECT_GT(r.summary.max_tracking_error, 0.01);  // the limits do not allow the task
}

TEST(QpConstraints, JointRangeBecomesAVelocityBound) {
  // joint 1 may not pass 0.25 rad; the task would drive it further
  json doc = free_circle();
  doc["duration"] = 3.0;
  doc["robot"]["limits"] = {{"lower", {-3, -3, -3, -3}}, {"upper", {0.25, 3, 3, 3}}};
  const auto r = run_scenario(doc, "qp_constraints");
  EXPECT_FALSE(r.summary.joint_limit_violated);
  for (const Frame& f : r.frames) EXPECT_LE(f.q[0], 0.25 + 1e-12);
}

TEST(QpConstraints, ARunAfterResetRepeatsBitForBit) {
  Simulator sim(load_scenario_file(test::source_path("scenarios/20_qiu_circle.json")));
  test::expect_repeats_after_reset(sim);
}

TEST(QpConstraints, ParametersAreValidated) {
  const MethodInfo* info = find_method("qp_constraints");
  ASSERT_NE(info, nullptr);
  for (const ParamSpec& spec : info->params) EXPECT_EQ(param_problem(spec, spec.def), "") << spec.name;
  Simulator sim(parse_scenario([] {
    json d = free_circle();
    d["method"] = {{"name", "qp_constraints"}};
    return d;
  }()));
  EXPECT_THROW(sim.set_param("d_s", -1.0), ParamError);
  EXPECT_THROW(sim.set_param("sigma", 0.0), ParamError);
  EXPECT_NO_THROW(sim.set_param("slack_weight", 1e4));
  sim.step();
}

}  // namespace
}  // namespace rrlab
