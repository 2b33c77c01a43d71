// Zhang et al.: avoidance manipulability, AMSI/AMSIP, the 1-step GA and
// the multi-preview velocity law; the paper's comparison scenarios.
#include <gtest/gtest.h>

#include <Eigen/SVD>
#include <cstring>

#include <rrlab/methods/multi_preview_avoidance.hpp>
#include <rrlab/methods/multi_preview_ga.hpp>
#include <rrlab/methods/registry.hpp>

#include "engine/sim_helpers.hpp"
#include "engine/test_models.hpp"

namespace rrlab {
namespace {

using nlohmann::json;
using test::planar_robot;

// The paper's Fig. 5 example: four 0.25 m links, hand at r = (0.6, 0.3).
const std::vector<double> kFig5Q = {1.396, -0.524, -0.631, -1.153};

Model planar_model(int links, double length) {
  return make_planar(std::vector<PlanarLinkSpec>(links, PlanarLinkSpec{length, 0.0}), {0, 0});
}

Eigen::VectorXd to_vector(const std::vector<double>& v) {
  return Eigen::Map<const Eigen::VectorXd>(v.data(), Eigen::Index(v.size()));
}

// ¹M_i = J_i (I − J_n⁺J_n) computed directly, and its SVD.
Eigen::JacobiSVD<Eigen::MatrixXd> direct_svd(const Model& model, const KinematicsData& kin,
                                              const Eigen::MatrixXd& jn, int point) {
  Eigen::MatrixXd j3(3, model.dof());
  point_jacobian_linear(model, kin, point, kin.link_end.col(point), j3);
  const Eigen::MatrixXd n = Eigen::MatrixXd::Identity(model.dof(), model.dof()) -
                            jn.completeOrthogonalDecomposition().pseudoInverse() * jn;
  const Eigen::MatrixXd m = j3.topRows(2) * n;
  return Eigen::JacobiSVD<Eigen::MatrixXd>(m, Eigen::ComputeFullU);
}

TEST(MultiPreviewAvoidance, UnitBallVolumesOfEq19) {
  EXPECT_DOUBLE_EQ(unit_ball_volume(1), 2.0);
  EXPECT_DOUBLE_EQ(unit_ball_volume(2), M_PI);
  EXPECT_DOUBLE_EQ(unit_ball_volume(3), 4.0 * M_PI / 3.0);
  EXPECT_DOUBLE_EQ(unit_ball_volume(4), M_PI * M_PI / 2.0);
}

TEST(MultiPreviewAvoidance, Fig5EllipsoidsMatchADirectSvd) {
  const Model model = planar_model(4, 0.25);
  KinematicsData kin(model);
  forward_kinematics(model, to_vector(kFig5Q), kin);
  EXPECT_NEAR(kin.end_effector().translation().x(), 0.6, 2e-3);
  EXPECT_NEAR(kin.end_effector().translation().y(), 0.3, 2e-3);
  Eigen::MatrixXd jn(2, 4);
  task_jacobian(model, kin, TaskSpace::xy, jn);

  AvoidanceManipulability am(model, TaskSpace::xy);
  const double amsi = am.compute(model, kin, jn);
  ASSERT_EQ(am.point_count(), 3);
  double direct_amsi = 0;
  for (int i = 0; i < 3; ++i) {
    const auto svd = direct_svd(model, kin, jn, i);
    const AvoidanceEllipsoid& e = am.ellipsoid(i);
    std::cout << "[ fig5 ] P" << i + 1 << " sigma " << e.sigma.head<2>().transpose() << " rank " << e.rank
              << " axis1 " << e.directions.col(0).head<2>().transpose() << "\n";
    for (int k = 0; k < 2; ++k) {
      EXPECT_NEAR(e.sigma[k], svd.singularValues()[k], 1e-9) << "point " << i << " sigma " << k;
      if (svd.singularValues()[k] > 1e-6) {  // axis direction up to sign
        EXPECT_NEAR(std::abs(e.directions.col(k).head<2>().dot(svd.matrixU().col(k))), 1.0, 1e-9);
      }
    }
    EXPECT_EQ(e.centre, Eigen::Vector3d(kin.link_end.col(i)));
    // the paper: ¹P_1 and ¹P_3 are lines (partial), ¹P_2 a whole ellipse (complete)
    EXPECT_EQ(e.rank, i == 1 ? 2 : 1) << "point " << i;
    EXPECT_EQ(e.volume_rank, i == 1 ? 2 : 1);
    const double v = i == 1 ? M_PI * svd.singularValues()[0] * svd.singularValues()[1]
                            : 2.0 * svd.singularValues()[0];  // eq. 18–20: an area, or a length
    EXPECT_NEAR(e.volume, v, 1e-9);
    direct_amsi += v;  // eq. 21 with a_i = 1
  }
  EXPECT_NEAR(amsi, direct_amsi, 1e-9);
  std::cout << "[ fig5 ] AMSI " << amsi << "\n";
}

TEST(MultiPreviewAvoidance, AmsiMatchesDirectSvdAtRandomConfigurations) {
  const Model model = planar_model(6, 0.4);
  KinematicsData kin(model);
  Eigen::MatrixXd jn(2, 6);
  AvoidanceManipulability am(model, TaskSpace::xy);
  for (unsigned seed = 1; seed <= 20; ++seed) {
    forward_kinematics(model, test::random_q(6, seed), kin);
    task_jacobian(model, kin, TaskSpace::xy, jn);
    const double amsi = am.compute(model, kin, jn);
    double direct = 0;
    for (int i = 0; i < am.point_count(); ++i) {
      const Eigen::VectorXd s = direct_svd(model, kin, jn, i).singularValues();
      const int r = am.ellipsoid(i).volume_rank;
      direct += r == 2 ? M_PI * s[0] * s[1] : 2.0 * s[0];
      EXPECT_EQ(r, i == 0 || i == am.point_count() - 1 ? 1 : 2);
    }
    EXPECT_NEAR(amsi, direct, 1e-9) << seed;
  }
}

TEST(MultiPreviewAvoidance, PluralAvoidanceMatricesOfEq15And17) {
  // seven links as in Fig. 6, first avoidance task at the tip of link 3
  const Model model = planar_model(7, 0.3);
  KinematicsData kin(model);
  forward_kinematics(model, test::random_q(7, 11), kin);
  Eigen::MatrixXd jn(2, 7), j3(3, 7);
  task_jacobian(model, kin, TaskSpace::xy, jn);
  std::vector<Eigen::MatrixXd> jacobians;
  for (int i = 0; i < 6; ++i) {
    point_jacobian_linear(model, kin, i, kin.link_end.col(i), j3);
    jacobians.push_back(j3.topRows(2));
  }
  const auto first = plural_avoidance_matrices(jacobians, jn, {});
  const auto second = plural_avoidance_matrices(jacobians, jn, {2});
  auto rank = [](const Eigen::MatrixXd& m) {
    const Eigen::VectorXd s = Eigen::JacobiSVD<Eigen::MatrixXd>(m).singularValues();
    return int((s.array() > 1e-9).count());  // absolute: a zero matrix has rank 0
  };
  EXPECT_EQ(rank(first[2]), 2);
  EXPECT_LT(second[2].norm(), 1e-12);  // eq. 15: ²M_i = 0 for the realised point
  // the paper's ranks after the task at link 3: rank(²M_j) = 1 for j = 1, 2, 4, 6 and 2 for j = 5
  const int expected[] = {1, 1, 0, 1, 2, 1};
  for (int j = 0; j < 6; ++j) {
    EXPECT_EQ(rank(second[j]), expected[j]) << "point " << j + 1;
    EXPECT_LE(second[j].norm(), first[j].norm() + 1e-12);  // ²P_j no larger than ¹P_j
  }
  // eq. 17: a third task at link 5 leaves points 1, 2, 4, 6 with one direction at most
  const auto third = plural_avoidance_matrices(jacobians, jn, {2, 4});
  EXPECT_LT(third[4].norm(), 1e-12);
  for (int j : {0, 1, 3, 5}) EXPECT_LE(rank(third[j]), 1);
}

TEST(MultiPreviewAvoidance, PotentialIsZeroOutsideTheBandAndMinusHeightAtContact) {
  DistanceTable table;
  table.resize(2, 1);
  table.at(0, 0).distance = 0.5;
  table.at(1, 0).distance = 0.0;
  EXPECT_DOUBLE_EQ(obstacle_potential(table, 0.2, 10.0), -10.0);
  table.at(1, 0).distance = 0.1;
  EXPECT_DOUBLE_EQ(obstacle_potential(table, 0.2, 10.0), -2.5);
  table.at(1, 0).distance = -0.1;
  EXPECT_LT(obstacle_potential(table, 0.2, 10.0), -10.0);
}

// The 1-step GA puts the hand on target and climbs AMSIP.
TEST(MultiPreviewGa, EvolvesTowardLargerAmsipWithTheHandOnTarget) {
  const Model model = planar_model(4, 0.25);
  ImaginaryManipulator arm(model, TaskSpace::xy);
  Scene scene;
  arm.set_scene(scene, 0.0);
  PreviewTarget target;
  target.position = Eigen::Vector3d(0.6, 0.3, 0);
  Rng rng(7);
  PreviewPopulation population(4, 50);
  GaSettings settings{30, 1, 0.1};
  Eigen::VectorXd q = to_vector(kFig5Q);
  const double fig5 = arm.evaluate(q, target).amsip;
  population.evolve(arm, target, rng, settings, 1);
  const double early = population.best_evaluation().fitness;
  population.evolve(arm, target, rng, settings, 40);
  const Evaluation& best = population.best_evaluation();
  EXPECT_GE(best.fitness, early);
  EXPECT_LT(best.residual, 1e-6);
  EXPECT_GT(best.amsi, fig5);  // the paper's configuration is not AMSI-optimal
  Eigen::VectorXd check = population.best();
  EXPECT_NEAR(arm.score(check, target).residual, 0.0, 1e-6);
  std::cout << "[ ga ] AMSI at Fig. 5 " << fig5 << ", after 41 generations " << best.amsi << "\n";
}

// --- the method inside the simulator -----------------------------------------

json fig5_hold() {
  return {{"dt", 0.01},
          {"duration", 3.0},
          {"seed", 3},
          {"robot", planar_robot(4, 0.25, 0.01, kFig5Q)},
          {"obstacles", {{{"id", "pin"}, {"shape", "sphere"}, {"center", {0.3, 0.55}}, {"radius", 0.05}}}},
          {"task", {{"space", "xy"},
                    {"trajectory", {{"type", "circle"}, {"center", {0.5, 0.3}}, {"radius", 0.1}}}}},
          {"method", {{"name", "multi_preview"}, {"params", {{"preview_time", 0.5}, {"kv", 2.0}}}}}};
}

TEST(MultiPreview, NullSpacePartNeverMovesTheHand) {
  Simulator sim(parse_scenario(fig5_hold()));
  const double largest_null = test::largest_null_space_motion(sim, 200);
  EXPECT_GT(largest_null, 1e-3);
}

TEST(MultiPreview, SwitchingToPathPlanningPlansFromTheCurrentConfiguration) {
  Simulator sim(parse_scenario(fig5_hold()));
  for (int k = 0; k < 50; ++k) sim.step();
  const auto& names = sim.diagnostic_names();
  const auto gap = std::find(names.begin(), names.end(), "preview_gap") - names.begin();
  EXPECT_GT(sim.frame().diagnostics[gap], 0.1);  // previews pull from afar
  sim.set_param("previews", 0);
  sim.step();
  EXPECT_LT(sim.frame().diagnostics[gap], 1e-12);  // the plan starts where the arm is
  EXPECT_EQ(sim.frame().overlays.ghosts.size(), 3u);
  for (int k = 0; k < 100; ++k) sim.step();
  EXPECT_LT(sim.frame().task_error, 1e-3);
}

bool same_frames(const std::vector<Frame>& a, const std::vector<Frame>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    if (a[i].q != b[i].q || a[i].qdot != b[i].qdot || a[i].diagnostics != b[i].diagnostics) return false;
    if (a[i].overlays.ghosts.size() != b[i].overlays.ghosts.size()) return false;
    for (size_t g = 0; g < a[i].overlays.ghosts.size(); ++g)
      if (a[i].overlays.ghosts[g] != b[i].overlays.ghosts[g]) return false;
  }
  return true;
}

TEST(MultiPreview, SeededRunsRepeatBitForBitAndSeedsMatter) {
  json doc = fig5_hold();
  doc["duration"] = 1.0;
  const auto a = test::run_scenario(doc, "multi_preview", doc["method"]["params"]);
  const auto b = test::run_scenario(doc, "multi_preview", doc["method"]["params"]);
  EXPECT_TRUE(same_frames(a.frames, b.frames));
  doc["seed"] = 4;
  const auto c = test::run_scenario(doc, "multi_preview", doc["method"]["params"]);
  EXPECT_FALSE(same_frames(a.frames, c.frames));
}

TEST(MultiPreview, OverlaysShowPreviewsOnTheFuturePathAndEllipsesAtLinkPoints) {
  Simulator sim(parse_scenario(fig5_hold()));
  sim.step();
  const Frame& f = sim.frame();
  ASSERT_EQ(f.overlays.ghosts.size(), 3u);
  ASSERT_EQ(f.overlays.ellipses.size(), 3u);
  KinematicsData kin(sim.model());
  for (int i = 0; i < 3; ++i) {
    forward_kinematics(sim.model(), f.overlays.ghosts[i], kin);
    const Eigen::Vector3d want = sim.task().target_position(f.t + (i + 1) * 0.5);
    EXPECT_LT((kin.end_effector().translation() - want).norm(), 1e-6) << "preview " << i + 1;
  }
  for (int i = 0; i < 3; ++i) EXPECT_EQ(f.overlays.ellipses[i].centre, Eigen::Vector3d(sim.kinematics().link_end.col(i)));
}

TEST(MultiPreview, ParameterChangesActOnTheNextStep) {
  Simulator sim(parse_scenario(fig5_hold()));
  sim.step();
  KinematicsData kin(sim.model());
  // preview_time
  sim.set_param("preview_time", 1.0);
  sim.step();
  forward_kinematics(sim.model(), sim.frame().overlays.ghosts[1], kin);
  EXPECT_LT((kin.end_effector().translation() - sim.task().target_position(sim.frame().t + 2.0)).norm(), 1e-6);
  // previews
  sim.set_param("previews", 1);
  sim.step();
  EXPECT_EQ(sim.frame().overlays.ghosts.size(), 1u);
  sim.set_param("previews", 2);
  sim.step();
  EXPECT_EQ(sim.frame().overlays.ghosts.size(), 2u);
  // weights: the pulled-toward configuration Σ k̂_i q̃_i (the gap diagnostic) follows k1..k3
  const auto& names = sim.diagnostic_names();
  const int gap = int(std::find(names.begin(), names.end(), "preview_gap") - names.begin());
  for (auto [k1, k2] : {std::pair{1.0, 0.0}, std::pair{0.0, 1.0}, std::pair{0.2, 0.6}}) {
    sim.set_param("k1", k1);
    sim.set_param("k2", k2);
    sim.step();
    const Frame& f = sim.frame();
    Eigen::VectorXd combined = Eigen::VectorXd::Zero(4);
    for (int i = 0; i < 2; ++i) {
      Eigen::VectorXd g = f.overlays.ghosts[i];
      for (int j = 0; j < 4; ++j) g[j] = f.q[j] + std::remainder(g[j] - f.q[j], 2 * M_PI);
      combined += (i == 0 ? k1 : k2) / (k1 + k2) * g;
    }
    EXPECT_NEAR(f.diagnostics[gap], (combined - f.q).norm(), 1e-9) << k1 << " " << k2;
  }
  EXPECT_THROW(sim.set_param("previews", 4), ParamError);
  EXPECT_THROW(sim.set_param("k1", -0.1), ParamError);
}

TEST(MultiPreview, ListedWithValidDefaults) {
  const MethodInfo* info = find_method("multi_preview");
  ASSERT_NE(info, nullptr);
  for (const ParamSpec& spec : info->params) EXPECT_EQ(param_problem(spec, spec.def), "") << spec.name;
}


// --- the paper's comparison (Sec. VII, Figs 11-13), scenarios 30-32 --------

struct PaperRun {
  test::RunResult result;
  double first_collision = -1;  // s, -1 when none
};

PaperRun run_paper(const std::string& file) {
  Simulator sim(load_scenario_file(test::source_path("scenarios/" + file)));
  test::FrameLog log;
  PaperRun run;
  run.result.summary = run_to_end(sim, &log);
  run.result.frames = std::move(log.frames);
  for (const Frame& f : run.result.frames)
    if (f.collided) {
      run.first_collision = f.t;
      break;
    }
  return run;
}

TEST(MultiPreviewPaper, SinglePreviewCollidesNearThirtySecondsThreePreviewsDoNot) {
  const PaperRun single = run_paper("30_zhang_single_preview.json");
  const PaperRun multi = run_paper("31_zhang_multi_preview.json");
  // the paper: single preview (t̃ = 10 s) hits the object at t = 30 s
  EXPECT_TRUE(single.result.summary.collided);
  EXPECT_GT(single.first_collision, 29.0);  // 29.96 s
  EXPECT_LT(single.first_collision, 31.0);
  // a shallow collision: 2.3 mm into the object
  EXPECT_LT(single.result.summary.min_distance, -0.001);  // -0.00230 m
  EXPECT_GT(single.result.summary.min_distance, -0.005);
  // three previews (t̃ = 5 s, k = 0.3, 0.65, 0.05) track the whole path without collision
  EXPECT_FALSE(multi.result.summary.collided);
  EXPECT_GT(multi.result.summary.min_distance, 0.018);  // 0.0243 m
  EXPECT_LT(multi.result.summary.min_distance, 0.03);
  for (const PaperRun* run : {&single, &multi}) {
    EXPECT_LT(run->result.summary.max_tracking_error, 1e-3);
    EXPECT_EQ(run->result.summary.nonfinite_steps, 0);
  }
  // seeded: a second run gives the same frames, bit for bit
  EXPECT_TRUE(same_frames(single.result.frames, run_paper("30_zhang_single_preview.json").result.frames));
  EXPECT_TRUE(same_frames(multi.result.frames, run_paper("31_zhang_multi_preview.json").result.frames));
  std::cout << "[ paper ] single preview: first collision at t = " << single.first_collision
            << " s, min distance " << single.result.summary.min_distance << " m; three previews: min distance "
            << multi.result.summary.min_distance << " m\n";
}

// The equal-horizon control (scenario 34): one preview at t̃ = 8.75 s, the
// k-weighted mean horizon of scenario 31's three previews (0.3·5 + 0.65·10 +
// 0.05·15 s), also avoids the object. So scenario 30 against 31 does not
// isolate several previews from a shorter horizon (benchmarks/zhang-sensitivity.json).
TEST(MultiPreviewPaper, SinglePreviewAtTheMultiPreviewMeanHorizonAvoidsToo) {
  const PaperRun control = run_paper("34_zhang_equal_horizon.json");
  EXPECT_FALSE(control.result.summary.collided);
  EXPECT_GT(control.result.summary.min_distance, 0.008);  // 0.0122 m
  EXPECT_LT(control.result.summary.min_distance, 0.018);  // less than the three previews' 0.0243 m
  EXPECT_LT(control.result.summary.max_tracking_error, 1e-3);
  std::cout << "[ paper ] equal-horizon single preview (8.75 s): min distance "
            << control.result.summary.min_distance << " m\n";
}

// Scenario 35: the one surface of scripts/zhang-geometry-search's 429 where
// pinv collides, three previews avoid and one preview (at 10 s and at the
// 8.75 s mean horizon) collides: the paper's contrast, found by search.
TEST(MultiPreviewPaper, OnTheSearchedSurfaceThreePreviewsAvoidWhereOnePreviewAndPinvCollide) {
  const Scenario surface = load_scenario_file(test::source_path("scenarios/35_zhang_searched_surface.json"));
  const auto previews = [&](double count, double horizon) {  // scenario 31's parameters otherwise
    Scenario changed = surface;
    for (auto& [name, value] : changed.method.params) {
      if (name == "previews") value = count;
      if (name == "preview_time") value = horizon;
    }
    Simulator sim(changed);
    return run_to_end(sim, nullptr);
  };
  const Summary three = previews(3, 5.0);
  const Summary one = previews(1, 10.0);
  const Summary same_horizon = previews(1, 8.75);
  Simulator plain(surface, "pinv");
  const Summary pinv = run_to_end(plain, nullptr);
  EXPECT_FALSE(three.collided);
  EXPECT_GT(three.min_distance, 0.002);  // 0.0043 m: thin
  EXPECT_LT(three.max_tracking_error, 0.03);
  EXPECT_TRUE(one.collided);             // −0.0223 m
  EXPECT_TRUE(same_horizon.collided);    // −0.0127 m
  EXPECT_LT(pinv.min_distance, -0.05);   // −0.106 m
  std::cout << "[ paper ] searched surface: three previews " << three.min_distance << " m, one preview "
            << one.min_distance << " m (8.75 s: " << same_horizon.min_distance << " m), pinv " << pinv.min_distance
            << " m\n";
}

TEST(MultiPreviewPaper, PathPlanningTracksWithoutCollisionAndTheMostAmsip) {
  const PaperRun plan = run_paper("32_zhang_path_planning.json");
  const PaperRun multi = run_paper("31_zhang_multi_preview.json");
  EXPECT_FALSE(plan.result.summary.collided);
  EXPECT_LT(plan.result.summary.max_tracking_error, 2e-3);
  const std::vector<std::string> names = find_method("multi_preview")->make({Model(make_planar({{1.0, 0.0}, {1.0, 0.0}}, {0, 0})),
                                                         TaskSpace::xy, 0})->diagnostic_names();
  const auto amsip = std::find(names.begin(), names.end(), "amsip") - names.begin();
  auto mean_amsip = [amsip](const PaperRun& run) {
    double sum = 0;
    for (const Frame& f : run.result.frames) sum += f.diagnostics[amsip];
    return sum / double(run.result.frames.size());
  };
  // the paper (Fig. 12): the planned path keeps ¹S at the peaks
  EXPECT_GT(mean_amsip(plan), mean_amsip(multi));
  std::cout << "[ paper ] mean AMSIP: path planning " << mean_amsip(plan) << ", three previews " << mean_amsip(multi)
            << "\n";
}


TEST(MultiPreviewPaper, Fig5ScenarioDrawsTwoLinesAndAnEllipse) {
  Simulator sim(load_scenario_file(test::source_path("scenarios/33_zhang_fig5_ellipsoids.json")));
  sim.step();
  const Overlays& o = sim.frame().overlays;
  ASSERT_EQ(o.ellipses.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    const Eigen::Matrix3d& axes = o.ellipses[i].axes;
    EXPECT_GT(axes.col(0).norm(), 0.05) << i;
    // ¹P_1, ¹P_3: segments (second semi-axis zero); ¹P_2: a full ellipse
    if (i == 1) EXPECT_GT(axes.col(1).norm(), 0.04);
    else EXPECT_LT(axes.col(1).norm(), 1e-6) << i;
    EXPECT_LT(axes.col(0).dot(axes.col(1)), 1e-12);  // perpendicular semi-axes
  }
}

}  // namespace
}  // namespace rrlab
