// Chen et al. (2002) posture generation: criteria and the paper's simulations.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>

#include <rrlab/generators/generators.hpp>
#include <rrlab/methods/posture_generation_criteria.hpp>
#include <rrlab/methods/registry.hpp>

#include "engine/sim_helpers.hpp"
#include "engine/test_models.hpp"

namespace rrlab {
namespace {

const double kLimit = 135.0 * M_PI / 180.0;

test::RunResult run_posture(const std::string& file, const std::string& method) {
  std::ifstream in(test::source_path("scenarios/" + file));
  nlohmann::json doc = nlohmann::json::parse(in);
  const nlohmann::json params = method == "posture_generation" ? doc["method"]["params"] : nlohmann::json::object();
  return test::run_scenario(doc, method, params);
}

// Largest |q_j| over the run for joints with a finite limit in the model.
double max_limited_joint(const test::RunResult& r, const Model& model) {
  double m = 0;
  for (const Frame& f : r.frames)
    for (int j = 0; j < f.q.size(); ++j)
      if (std::isfinite(model.limits.upper[j])) m = std::max(m, std::abs(f.q[j]));
  return m;
}

Model model_of(const std::string& file) { return load_scenario_file(test::source_path("scenarios/" + file)).model; }

TEST(ChenCriteria, ConeIsFlatOutsideAndItsSlopeIsTheDerivative) {
  const double phi = 0.6;
  EXPECT_FALSE(chen::cone(0.7, phi).active);
  EXPECT_EQ(chen::cone(0.7, phi).value, 1.0);
  for (double psi : {0.05, 0.2, 0.4, 0.55}) {
    const double h = 1e-6;
    const double fd = (chen::cone(psi + h, phi).value - chen::cone(psi - h, phi).value) / (2 * h);
    EXPECT_NEAR(chen::cone(psi, phi).slope, fd, 1e-5) << psi;
    EXPECT_GT(chen::cone(psi, phi).slope, chen::cone(psi + 0.05, phi).slope);  // steeper nearer the obstacle
  }
  // finite at Ψ = 0 and past a limit (Ψ < 0): the push stays on
  EXPECT_GT(chen::cone(0.0, phi).slope, 0.0);
  EXPECT_TRUE(std::isfinite(chen::cone(-0.1, phi).slope));
  EXPECT_NEAR(chen::cone(0.0, phi).value, 0.0, 1e-12);
}

TEST(ChenCriteria, IncludedAngleDerivativeMatchesRotation) {
  const Eigen::Vector3d b(1.0, 0.3, 0), axis(0, 0, 1);
  const double a0 = 0.2;
  auto u_at = [](double a) { return Eigen::Vector3d(2 * std::cos(a), 2 * std::sin(a), 0); };
  const Eigen::Vector3d u = u_at(a0), du = axis.cross(u);
  const chen::Angle angle = chen::included_angle(u, du, b);
  const double h = 1e-6;
  const double fd =
      (chen::included_angle(u_at(a0 + h), du, b).psi - chen::included_angle(u_at(a0 - h), du, b).psi) / (2 * h);
  EXPECT_NEAR(angle.dpsi, fd, 1e-6);
}

TEST(ChenCriteria, AdjacentAndElasticGradientsMatchFiniteDifferences) {
  const Eigen::Vector3d d(0.3, -0.2, 0), axis(0, 0, 1);
  auto u_at = [](double a) { return Eigen::Vector3d(1.5 * std::cos(a), 1.5 * std::sin(a), 0); };
  const double a0 = 0.4, h = 1e-6, eta = 2.0;  // ‖D̄‖ ≈ 1.33 < η
  // D̄ = u − D with D fixed
  const Eigen::Vector3d du = axis.cross(u_at(a0));
  const chen::Adjacent t = chen::adjacent_term(u_at(a0) - d, du, eta);
  ASSERT_TRUE(t.active);
  const double fd = (chen::adjacent_term(u_at(a0 + h) - d, du, eta).value -
                     chen::adjacent_term(u_at(a0 - h) - d, du, eta).value) / (2 * h);
  EXPECT_NEAR(t.grad, fd, 1e-5);
  const Eigen::Vector3d e(0.2, 1.0, 0);
  const chen::Elastic el = chen::elastic_term(u_at(a0), du, e);
  const double fde =
      (chen::elastic_term(u_at(a0 + h), du, e).value - chen::elastic_term(u_at(a0 - h), du, e).value) / (2 * h);
  EXPECT_NEAR(el.grad, fde, 1e-6);
}

TEST(ChenSim3, MinimumNormPassesTheLimitPostureGenerationKeepsEveryJointInside) {
  const std::string file = "18_chen_sim3_joint_limits.json";
  const Model model = model_of(file);
  const auto pinv = run_posture(file, "pinv");
  const auto chen = run_posture(file, "posture_generation");
  const double pinv_max = max_limited_joint(pinv, model), chen_max = max_limited_joint(chen, model);
  std::printf("[ Chen Sim 3 ] largest |bending joint|: pinv %.3f rad, posture_generation %.3f rad (limit %.3f); "
              "max tracking error pinv %.5f, posture_generation %.5f\n",
              pinv_max, chen_max, kLimit, pinv.summary.max_tracking_error, chen.summary.max_tracking_error);
  EXPECT_GE(pinv_max, 2.36);  // Fig. 8: a joint reaches or passes 2.36 rad
  EXPECT_TRUE(pinv.summary.joint_limit_violated);
  EXPECT_FALSE(chen.summary.joint_limit_violated);  // Fig. 9: every joint inside its limits
  EXPECT_LT(chen_max, kLimit);
  EXPECT_LT(chen.summary.max_tracking_error, 0.01);
  EXPECT_LT(chen.summary.final_tracking_error, 0.01);
}

// Fig. 7b: under minimum norm the paper's joint 6 (the bending joint between
// its third and fourth links, base link counted) reaches its limit. In rrlab
// it is joint 4 (between the second and third links) that crosses, at
// t = 36.85 s, 0.105 rad past; joint 6 peaks at 1.339 rad. Not matched, and
// not explained by eq. 11's order: a pure-Python pinv of the same scenario
// (closed loop, quintic law) reproduces rrlab exactly with the serial
// O_i = R_1⋯R_i L_i, and with the printed O_i = R_i⋯R_1 L_i no joint crosses
// at all (the start hand moves to (−2.75, −0.64, 3)); an active instead of the
// printed passive R_x, R_z·R_x per pair, or L_i along y do not make joint 6
// cross either. The paper does not give L_i's direction, the base link's
// orientation or the frame of the goal (−4, 1, 0), on which which joint
// crosses depends: the gap is a scenario convention the paper leaves open.
TEST(ChenSim3, UnderPinvJointFourCrossesNotThePapersJointSix) {
  const std::string file = "18_chen_sim3_joint_limits.json";
  const auto pinv = run_posture(file, "pinv");
  int first = -1;
  double t_first = 0, peak[8] = {0};
  for (const Frame& f : pinv.frames)
    for (int j = 1; j < 8; j += 2) {
      peak[j] = std::max(peak[j], std::abs(f.q[j]));
      if (first < 0 && std::abs(f.q[j]) > kLimit) first = j, t_first = f.t;
    }
  std::printf("[ Chen Sim 3 ] pinv: first bending joint past 2.356 rad: joint %d at t = %.2f s; peaks joint 2 %.3f, "
              "4 %.3f, 6 %.3f, 8 %.3f rad\n",
              first + 1, t_first, peak[1], peak[3], peak[5], peak[7]);
  EXPECT_EQ(first + 1, 4);          // the paper: joint 6
  EXPECT_NEAR(t_first, 36.8, 0.5);  // measured 36.80-36.85 s
  EXPECT_NEAR(peak[3], 2.461, 0.01);
  EXPECT_LT(peak[5], 1.4);          // joint 6: measured 1.339 rad, far from 2.356
}

// The defaults (ω 1, w_limits 2) hold the limits on generated
// planar_limits cases (seed 2001, not used for tuning; pinv crosses a limit
// on every one by construction). Measured: no limit crossed on 10 of 10,
// least margin 0.134 rad, tracking error at most 3.3 mm (9 of 10 below 3 mm).
TEST(PostureGenerationDefaults, HoldLimitsWherePinvDoesNot) {
  int pinv_crossed = 0, held = 0;
  for (int index = 0; index < 10; ++index) {
    const nlohmann::json doc = generate_scenario("planar_limits", nlohmann::json::object(), 2001, index);
    pinv_crossed += test::run_scenario(doc, "pinv").summary.joint_limit_violated;
    const auto chen = test::run_scenario(doc, "posture_generation");
    std::printf("[ defaults ] planar_limits 2001/%d posture_generation min limit margin %.3f rad, error %.4f m\n",
                index, chen.summary.min_joint_limit_margin, chen.summary.max_tracking_error);
    held += !chen.summary.joint_limit_violated && chen.summary.max_tracking_error < 0.003;
  }
  EXPECT_EQ(pinv_crossed, 10);
  EXPECT_GE(held, 9);  // measured 10
}

// Chen's Γ3 against minimum norm, paired per case, where minimum norm
// crosses a limit by 10-20° (planar_limits seed 2001, cases 0-59, not used
// for tuning). With the paper's ω 0.1 and w_limits 1 the method crossed
// farther than pinv on generated cases (seed 77: 2 of 200, one by 49° where
// pinv crossed by 4°); with the defaults it is never deeper here.
TEST(PostureGenerationAtScale, NeverCrossesFartherThanPinvWhereItCrossesByTenToTwentyDegrees) {
  int in_band = 0, deeper = 0, crossed = 0;
  for (int index = 0; index < 60; ++index) {
    const nlohmann::json doc = generate_scenario("planar_limits", nlohmann::json::object(), 2001, index);
    const double pinv = test::run_scenario(doc, "pinv").summary.min_joint_limit_margin * 180.0 / M_PI;
    if (pinv > -10.0 || pinv < -20.0) continue;
    ++in_band;
    const double chen = test::run_scenario(doc, "posture_generation").summary.min_joint_limit_margin * 180.0 / M_PI;
    std::printf("[ defaults ] planar_limits 2001/%d pinv margin %.1f deg, posture_generation %.1f deg\n", index, pinv, chen);
    deeper += chen < pinv;
    crossed += chen < 0;
  }
  EXPECT_GE(in_band, 5);  // 6: cases 4, 7, 10, 26, 30 and 51; posture_generation held every limit on all six
  EXPECT_EQ(deeper, 0);
  EXPECT_LE(crossed, in_band / 10);
}

TEST(ChenSim1, Planar12TracksWithoutCollisionOrLimit) {
  const std::string file = "16_chen_sim1_planar12.json";
  const auto chen = run_posture(file, "posture_generation");
  const auto sr = run_posture(file, "sr_task_priority");
  std::printf("[ Chen Sim 1 ] posture_generation: max tracking error %.5f, min distance %.4f, largest |q| %.3f rad; "
              "sr_task_priority min distance %.4f\n",
              chen.summary.max_tracking_error, chen.summary.min_distance, max_limited_joint(chen, model_of(file)),
              sr.summary.min_distance);
  EXPECT_FALSE(chen.summary.collided);
  EXPECT_GT(chen.summary.min_distance, 0.1);
  EXPECT_FALSE(chen.summary.joint_limit_violated);
  EXPECT_LT(chen.summary.max_tracking_error, 0.01);
  EXPECT_TRUE(sr.summary.collided);  // the closest-point baseline does not make it
}

TEST(ChenSim2, Spatial16ThroughTheWindow) {
  const std::string file = "17_chen_sim2_spatial16_window.json";
  const auto chen = run_posture(file, "posture_generation");
  double azimuth = 0;  // the unlimited x joints (reported)
  for (const Frame& f : chen.frames)
    for (int j = 2; j < f.q.size(); j += 2) azimuth = std::max(azimuth, std::abs(f.q[j]));
  std::printf("[ Chen Sim 2 ] posture_generation: max tracking error %.5f, min distance %.4f, largest |bending "
              "joint| %.3f rad, largest |azimuth joint| %.3f rad\n",
              chen.summary.max_tracking_error, chen.summary.min_distance, max_limited_joint(chen, model_of(file)),
              azimuth);
  EXPECT_FALSE(chen.summary.collided);
  EXPECT_GT(chen.summary.min_distance, 0.03);  // measured 0.041 (links of radius 0.05)
  EXPECT_FALSE(chen.summary.joint_limit_violated);
  EXPECT_LT(chen.summary.max_tracking_error, 0.01);
  const auto plain = run_posture(file, "pinv");
  std::printf("[ Chen Sim 2 ] pinv min distance %.4f\n", plain.summary.min_distance);
  EXPECT_TRUE(plain.summary.collided);  // the window is narrow enough to matter
}

TEST(PostureGenerationParams, ValidatedAndChangeable) {
  const Model model = make_planar({{1, 0}, {1, 0}, {1, 0}, {1, 0}}, {0, 0});
  auto method = find_method("posture_generation")->make({model, TaskSpace::xy, 0, 1});
  EXPECT_THROW(method->set_param("eta", 0.0), ParamError);
  EXPECT_THROW(method->set_param("influence_deg", 200), ParamError);
  EXPECT_THROW(method->set_param("elastic_first_link", 2), ParamError);
  method->set_param("omega", 0.5);
  EXPECT_EQ(method->param("omega"), 0.5);
  const auto& names = method->diagnostic_names();
  for (const char* n : {"Gamma1", "Gamma2", "Gamma3", "Gamma4", "gamma1", "gamma2", "constrained_link"})
    EXPECT_NE(std::find(names.begin(), names.end(), n), names.end()) << n;
}

}  // namespace
}  // namespace rrlab
