// Kapoor, Cetin & Tesar direct search: the 10-DOF square-and-circle example
// (scenarios 22, 23), the DM weight rule, weights changed at run time, and
// the option generation on a small planar arm.
#include <gtest/gtest.h>

#include <rrlab/generators/generators.hpp>
#include <rrlab/methods/registry.hpp>

#include "engine/sim_helpers.hpp"
#include "engine/test_models.hpp"

namespace rrlab {
namespace {

using nlohmann::json;

struct SearchRun {
  Summary summary;
  std::vector<Frame> frames;
  std::vector<std::string> names;
  double diag(size_t frame, const std::string& name) const {
    for (size_t i = 0; i < names.size(); ++i)
      if (names[i] == name) return frames[frame].diagnostics[static_cast<Eigen::Index>(i)];
    ADD_FAILURE() << "no diagnostic " << name;
    return 0;
  }
  double max_diag(const std::string& name, size_t from = 0) const {
    double m = -1e300;
    for (size_t i = from; i < frames.size(); ++i) m = std::max(m, diag(i, name));
    return m;
  }
};

SearchRun run_sim(Simulator& sim) {
  test::FrameLog log;
  SearchRun r;
  r.summary = run_to_end(sim, &log);
  r.frames = std::move(log.frames);
  r.names = sim.diagnostic_names();
  return r;
}

SearchRun run_file(const std::string& file) {
  Simulator sim(load_scenario_file(test::source_path(file)));
  return run_sim(sim);
}

TEST(DirectSearchPaper, KapoorSquareAndCircleAreTrackedIn6d) {
  const SearchRun r = run_file("scenarios/22_kapoor_square_circle.json");
  double max_position = 0, max_orientation = 0;
  int min_feasible = 81, switched = 0;
  for (size_t i = 1; i < r.frames.size(); ++i) {  // frame 0: the reference starts before the arm moved
    max_position = std::max(max_position, r.frames[i].task_error);
    max_orientation = std::max(max_orientation, r.frames[i].orientation_error);
    min_feasible = std::min(min_feasible, static_cast<int>(r.diag(i, "feasible_options")));
    switched += r.diag(i, "block_switched") > 0;
    EXPECT_EQ(r.diag(i, "options"), 81);
  }
  EXPECT_LT(max_position, 1e-8);
  EXPECT_LT(max_orientation, 1e-8);
  EXPECT_GT(min_feasible, 0);
  EXPECT_EQ(switched, 0);  // the paper's block (joints 1, 2, 3, 5 perturbed) throughout
  EXPECT_FALSE(r.summary.joint_limit_violated);
  EXPECT_EQ(r.summary.nonfinite_steps, 0);
  std::printf("kapoor square+circle: max position error %.2e m, orientation %.2e rad, min feasible options %d, "
              "block switched on %d of %zu steps\n",
              max_position, max_orientation, min_feasible, switched, r.frames.size());
}

// The paper's method as published: no recovery step, no block switch, no
// clearance criterion (rrlab's additions; the scenarios set the block switch
// and take the recovery step's default). On scenario 22 none acts: the same
// run bit for bit, so the reproduction's paper and (rrlab) rows share the
// shipped outcome and differ on the nudged copies only (a hand moved off the
// path stalls without the recovery step). On scenario 23 the block switch
// acts (333 steps) after DM's peak: the run ends elsewhere, but the DM rule's
// outcome is the same (peak 4.70, below the equal-weight 5.54).
SearchRun run_with_the_papers_values(const char* file) {
  Simulator sim(load_scenario_file(test::source_path(file)));
  sim.set_param("recovery_damping", 0.0);
  sim.set_param("block_switch", 0.0);
  sim.set_param("w_obstacle", 0.0);
  return run_sim(sim);
}

TEST(DirectSearchPaper, ThePapersValuesGiveTheSameOutcomesOnTheShippedRuns) {
  const SearchRun shipped = run_file("scenarios/22_kapoor_square_circle.json");
  const SearchRun paper = run_with_the_papers_values("scenarios/22_kapoor_square_circle.json");
  EXPECT_EQ(shipped.summary.final_q, paper.summary.final_q);
  EXPECT_EQ(shipped.summary.min_joint_limit_margin, paper.summary.min_joint_limit_margin);
  const SearchRun rule = run_file("scenarios/23_kapoor_dm_rule.json");
  const SearchRun rule_paper = run_with_the_papers_values("scenarios/23_kapoor_dm_rule.json");
  EXPECT_NE(rule.summary.final_q, rule_paper.summary.final_q);  // the block switch acts in 23
  EXPECT_EQ(rule_paper.max_diag("block_switched"), 0);
  EXPECT_NEAR(rule_paper.max_diag("current_dm"), rule.max_diag("current_dm"), 1e-9);  // 4.70
  EXPECT_LT(rule_paper.max_diag("current_dm"), 5.54 - 0.5);
  EXPECT_LT(rule_paper.summary.max_tracking_error, 1e-3);
}

TEST(DirectSearchPaper, DmRuleShiftsWeightsAndKeepsDexterityBelowTheEqualWeightPeak) {
  // relative threshold: the paper switched at 250 of the more than 300 its
  // equal-weight run reached (0.83); here 0.83 of scenario 22's peak DM at
  // the same characteristic length L = 0.4 m
  const SearchRun plain = run_file("scenarios/22_kapoor_square_circle.json");
  const SearchRun rule = run_file("scenarios/23_kapoor_dm_rule.json");
  ASSERT_EQ(plain.frames.size(), rule.frames.size());
  const double peak = plain.max_diag("current_dm");
  EXPECT_NEAR(peak, 5.54, 0.01);  // 5.5438: scenario 23's dm_rule_reference
  const double threshold = 0.83 * 5.54;
  EXPECT_EQ(plain.max_diag("dm_rule_active"), 0);
  size_t on = 0;
  while (on < rule.frames.size() && rule.diag(on, "dm_rule_active") == 0) ++on;
  ASSERT_LT(on, rule.frames.size());
  EXPECT_GE(rule.diag(on, "current_dm"), threshold);
  EXPECT_NEAR(static_cast<double>(on), 433, 30);  // step 433, t = 7.2 s
  EXPECT_DOUBLE_EQ(rule.diag(on, "w_jra"), 0.8);
  EXPECT_DOUBLE_EQ(rule.diag(on, "w_jvm"), 0.2);
  EXPECT_DOUBLE_EQ(rule.diag(on, "w_dm"), 1.0);
  // Fig 4: with the rule DM turns away below the equal-weight peak while JRA
  // and JVM grow
  EXPECT_LT(rule.max_diag("current_dm"), peak - 0.5);  // 4.70 vs 5.54
  double plain_jra = 0, rule_jra = 0, plain_jvm = 0, rule_jvm = 0;
  for (size_t i = on; i < rule.frames.size(); ++i) {
    plain_jra += plain.diag(i, "jra"), rule_jra += rule.diag(i, "jra");
    plain_jvm += plain.diag(i, "jvm"), rule_jvm += rule.diag(i, "jvm");
  }
  EXPECT_GT(rule_jra, 1.3 * plain_jra);  // mean 3.29 vs 2.13
  EXPECT_GT(rule_jvm, plain_jvm);
  EXPECT_LT(rule.summary.max_tracking_error, 1e-3);
  std::printf("kapoor DM: max (1,1,1) %.1f, with the rule %.1f (on at step %zu); mean JRA after %.2f vs %.2f, "
              "mean JVM %.2e vs %.2e\n",
              plain.max_diag("dm"), rule.max_diag("dm"), on, plain_jra / (rule.frames.size() - on),
              rule_jra / (rule.frames.size() - on), plain_jvm / (rule.frames.size() - on),
              rule_jvm / (rule.frames.size() - on));
}

TEST(DirectSearch, DmDependsOnTheCharacteristicLength) {
  // DM = σmax/σmin mixes m and rad: at q0 of scenario 22 it is 3.12 with
  // L = 0.4 m (about its minimum over L), 34.1 with L = 1 inch, 4.09 with 0.8 m
  Scenario scenario = load_scenario_file(test::source_path("scenarios/22_kapoor_square_circle.json"));
  auto dm_at_start = [&](double length) {
    Simulator sim(scenario);
    sim.set_param("dm_length", length);
    sim.set_total_steps(1);
    test::FrameLog log;
    run_to_end(sim, &log);
    const std::vector<std::string> names = sim.diagnostic_names();
    const auto at = std::find(names.begin(), names.end(), "current_dm") - names.begin();
    return log.frames.front().diagnostics[at];
  };
  EXPECT_NEAR(dm_at_start(0.4), 3.124, 0.01);
  EXPECT_NEAR(dm_at_start(0.0254), 34.11, 0.05);
  EXPECT_NEAR(dm_at_start(0.8), 4.088, 0.01);
  EXPECT_GT(dm_at_start(0.3), dm_at_start(0.4));
  EXPECT_GT(dm_at_start(0.5), dm_at_start(0.4));
}

TEST(DirectSearch, WeightChangedMidRunActsFromTheNextStep) {
  const Scenario scenario = load_scenario_file(test::source_path("scenarios/22_kapoor_square_circle.json"));
  Simulator a(scenario), b(scenario);
  const int before = 60, after = 30;
  a.set_total_steps(before + after);
  b.set_total_steps(before + after);
  test::FrameLog log_a, log_b;
  for (int i = 0; i < before; ++i) {
    a.step(), b.step();
    log_a.frame(a.frame()), log_b.frame(b.frame());
  }
  b.set_param("w_dm", 0.0);  // from the dashboard: DM no longer counts
  b.set_param("w_jra", 0.0);
  for (int i = 0; i < after; ++i) {
    a.step(), b.step();
    log_a.frame(a.frame()), log_b.frame(b.frame());
  }
  for (int i = 0; i < before; ++i) ASSERT_EQ(log_a.frames[i].qdot, log_b.frames[i].qdot) << i;
  // the first step after the change already selects by JVM alone: the option
  // with the least joint motion differs from the (1,1,1) choice
  EXPECT_NE(log_a.frames[before].qdot, log_b.frames[before].qdot);
  int differing = 0;
  for (int i = before; i < before + after; ++i) differing += log_a.frames[i].qdot != log_b.frames[i].qdot;
  EXPECT_EQ(differing, after);
}

// 3-link planar arm, xy task: n − m = 1, so one perturbed joint, 3 options.
json three_link_circle() {
  return {{"dt", 0.01},
          {"duration", 2.0},
          {"robot", {{"kind", "planar"},
                     {"links", {{{"length", 1.0}}, {{"length", 0.8}}, {{"length", 0.6}}}},
                     {"q0", {0.3, -0.6, -1.0}},
                     {"limits", {{"lower", {-3, -3, -3}}, {"upper", {3, 3, 3}}}}}},
          {"task", {{"space", "xy"}, {"trajectory", {{"type", "circle"}, {"center", {1.6, 0.0}}, {"radius", 0.2}}}}},
          {"method", {{"name", "direct_search"}, {"params", {{"delta", 0.01}}}}}};
}

TEST(DirectSearch, OptionsMeetTheEndEffectorConstraintOnAPlanarArm) {
  Simulator sim(parse_scenario(three_link_circle()));
  const SearchRun r = run_sim(sim);
  for (size_t i = 1; i < r.frames.size(); ++i) {
    EXPECT_EQ(r.diag(i, "options"), 3);
    EXPECT_EQ(r.diag(i, "feasible_options"), 3) << i;
    EXPECT_LT(r.diag(i, "residual"), 1e-9);
    EXPECT_LT(r.frames[i].task_error, 1e-8);
  }
}

TEST(DirectSearch, JvmAloneChoosesTheUnperturbedOption) {
  // with only JVM weighted, the option that moves the joints least is the
  // one without perturbation (index 1 of −Δ, 0, +Δ) on a slow path
  json doc = three_link_circle();
  doc["method"]["params"] = {{"delta", 0.01}, {"w_jra", 0}, {"w_dm", 0}, {"w_obstacle", 0}};
  Simulator sim(parse_scenario(doc));
  const SearchRun r = run_sim(sim);
  for (size_t i = 1; i < r.frames.size(); ++i) EXPECT_EQ(r.diag(i, "chosen_option"), 1) << i;
}

TEST(DirectSearch, ObstacleClearanceCriterionPullsAway) {
  json doc = three_link_circle();
  doc["obstacles"] = {{{"shape", "point"}, {"position", {0.9, 0.6}}}};
  doc["method"]["params"] = {{"delta", 0.01}, {"w_jra", 0}, {"w_jvm", 0}, {"w_dm", 0}, {"w_obstacle", 1}};
  const SearchRun away = [&] {
    Simulator sim(parse_scenario(doc));
    return run_sim(sim);
  }();
  doc["method"]["params"]["w_obstacle"] = 0;
  doc["method"]["params"]["w_jvm"] = 1;
  const SearchRun still = [&] {
    Simulator sim(parse_scenario(doc));
    return run_sim(sim);
  }();
  EXPECT_GT(away.frames.back().min_distance, still.frames.back().min_distance + 0.05);
  EXPECT_LT(away.summary.final_tracking_error, 1e-8);
}

TEST(DirectSearch, ARunAfterResetRepeatsBitForBit) {
  // the DM rule latches during a run; a reset starts it afresh
  Simulator sim(load_scenario_file(test::source_path("scenarios/23_kapoor_dm_rule.json")));
  sim.set_total_steps(300);
  test::expect_repeats_after_reset(sim);
}

TEST(DirectSearch, ParametersAreValidated) {
  const MethodInfo* info = find_method("direct_search");
  ASSERT_NE(info, nullptr);
  for (const ParamSpec& spec : info->params) EXPECT_EQ(param_problem(spec, spec.def), "") << spec.name;
  Simulator sim(parse_scenario(three_link_circle()));
  EXPECT_THROW(sim.set_param("w_dm", 2.0), ParamError);
  EXPECT_THROW(sim.set_param("delta", -0.1), ParamError);
  EXPECT_NO_THROW(sim.set_param("perturb_mask", 4));
  sim.step();
  EXPECT_TRUE(sim.frame().qdot.allFinite());
}

// A block that goes singular (a spatial_clutter case as drawn before cases
// carried witnesses, kept as a file: 7-DOF, joints 4, 6, 7 compensate,
// σ_min 0.002 m/rad at t = 0.09 s) left every option infeasible and the arm
// standing still for the rest of the run.
TEST(DirectSearch, ASingularBlockNoLongerFreezesTheArm) {
  const Scenario scenario = load_scenario_file(std::string(RRLAB_SOURCE_DIR) +
                                               "/tests/engine/methods/fixtures/direct_search_singular_block.json");
  auto run = [&](double block_switch, double recovery) {
    Scenario s = scenario;
    s.method.name = "direct_search";
    s.method.params = {{"block_switch", block_switch}, {"recovery_damping", recovery}};
    Simulator sim(s);
    return run_sim(sim);
  };
  const SearchRun fixed = run(0.0, 0.0), switching = run(0.02, 0.0), recovering = run(0.0, 0.05);
  EXPECT_GT(fixed.summary.max_tracking_error, 0.3);  // 0.61 m: frozen
  EXPECT_LT(switching.summary.max_tracking_error, 1e-5);  // 3.3e-7 m
  EXPECT_FALSE(switching.summary.joint_limit_violated);
  // the recovery step alone also unfreezes it: damped steps leave the singular block
  EXPECT_LT(recovering.summary.max_tracking_error, 2e-3);  // 6.1e-4 m
  EXPECT_FALSE(recovering.summary.joint_limit_violated);
}

// Kapoor's scheme starts with the hand on the path; started 2-4 cm off it
// (the path moved along x, y or z), with the scenario's velocity limits
// (60°/s), the recovery step brings the hand within 5 mm in at most 3 steps
// (0.05 s) and the run tracks from then on (checked over the first 4 s).
// Without it (recovery_damping 0) no option is feasible and the hand stays
// 2-4 cm off: over the whole 36 s run on 6 of these 9 starts, and the
// other 3 (the path moved along y) come back only after about 19.7 s.
TEST(DirectSearchPaper, AStartOffThePathComesBackWithinTwoSeconds) {
  const Scenario paper = load_scenario_file(std::string(RRLAB_SOURCE_DIR) + "/scenarios/22_kapoor_square_circle.json");
  int stuck_without = 0;
  for (double offset : {0.02, 0.03, 0.04}) {
    for (int axis = 0; axis < 3; ++axis) {
      SCOPED_TRACE(std::to_string(offset) + " m along axis " + std::to_string(axis));
      nlohmann::json doc = paper.json;
      for (auto& point : doc["task"]["trajectory"]["points"]) point[axis] = point[axis].get<double>() + offset;
      doc["method"]["params"]["recovery_damping"] = 0.05;
      Scenario s = parse_scenario(doc);
      Simulator sim(s);
      sim.set_total_steps(std::lround(4.0 / s.dt));
      double back_at = -1;  // the time from which the error stays below 5 mm
      while (!sim.done()) {
        sim.step();
        const Frame& f = sim.frame();
        if (f.task_error < 5e-3) {
          if (back_at < 0) back_at = f.t;
        } else {
          back_at = -1;
        }
      }
      EXPECT_GE(back_at, 0);
      EXPECT_LE(back_at, 2.0);
      doc["method"]["params"]["recovery_damping"] = 0.0;
      s = parse_scenario(doc);
      Simulator without(s);
      without.set_total_steps(std::lround(4.0 / s.dt));
      const Summary summary = run_to_end(without, nullptr);
      stuck_without += summary.final_tracking_error > 0.01;
    }
  }
  EXPECT_EQ(stuck_without, 9);
}

// The defaults on held-out planar_limits cases (seed 1001): joint limits held
// on every case, the task on 7 of 10 (before: 0 of 10 past a limit, 2 of 10
// tracked; pinv crosses a limit on all 10).
TEST(DirectSearch, DefaultsHoldLimitsAndTrackOnPlanarLimits) {
  int tracked = 0, violated = 0;
  for (int index = 0; index < 10; ++index) {
    Scenario s = parse_scenario(generate_scenario("planar_limits", nullptr, 1001, index));
    s.method.name = "direct_search";
    Simulator sim(s);
    const Summary summary = run_to_end(sim, nullptr);
    tracked += summary.max_tracking_error <= 0.01;
    violated += summary.joint_limit_violated;
  }
  EXPECT_EQ(violated, 0);
  EXPECT_GE(tracked, 6);  // 7
}

}  // namespace
}  // namespace rrlab
